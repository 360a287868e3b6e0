// Per-stage timings against the 30 Hz frame budget (33.3 ms): the spread, the blend and the two
// together, on the CPU reference and on CUDA, at 256², 1920×1080 and 3840×2160.
// CUDA is timed with events around the launches; each benchmark warms up first and reports the
// median of its repetitions. Run: build/default/bench/bleedsim_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/effects/blend/blend_stage.h"
#include "core/effects/spread/spread_tiles.h"
#include "core/physics/optics_tables.h"
#include "core/physics/pixel_kernels.h"
#include "core/runtime/backend.h"
#include "core/runtime/tissue.h"

namespace bleedsim {
namespace {

constexpr double kFrameBudgetMs = 1000.0 / 30.0;

struct Size {
  const char* name;
  int width, height;
};
const Size kSizes[] = {{"256x256", 256, 256}, {"1920x1080", 1920, 1080}, {"3840x2160", 3840, 2160}};
constexpr int kCutCount = 8;

// A steady scene: eight half-grown stains over a 0.05 mm/px panel, overlapping in pairs.
struct StageScene {
  std::unique_ptr<Backend> backend;
  PixelGrid grid;
  Scene scene;  // the panel, for the blend: unlit, the stain alone over the tissue
  Buffer cuts, stain, tissue, frame, tables;
  SpreadPixel spread_work{};

  StageScene(std::unique_ptr<Backend> b, const Size& size) : backend(std::move(b)) {
    grid = PixelGrid{size.width, size.height, 0.05f, 0.05f};
    const std::size_t pixels = std::size_t(size.width) * size.height;
    std::vector<SpreadCut> host_cuts;
    const float w_mm = size.width * 0.05f, h_mm = size.height * 0.05f;
    scene.domain = Domain{size.width, size.height, w_mm, h_mm};
    for (int c = 0; c < kCutCount; ++c)
      host_cuts.push_back({w_mm * (0.15f + 0.1f * c), h_mm * (c % 2 ? 0.4f : 0.6f), 0.15f * h_mm, 0.5f});
    // The cuts and their tile table, as the spread stage uploads them.
    SpreadUpload upload;
    upload.lay_out(host_cuts, 0, grid, spread_reach_per_mm(scene));
    cuts = backend->allocate(upload.bytes().size());
    backend->upload(cuts.data(), upload.bytes().data(), cuts.bytes());
    stain = backend->allocate(pixels * sizeof(float));
    spread_work = upload.pixel_work(cuts.data(), stain.as<float>());
    frame = backend->allocate(pixels * 4);
    tissue = backend->allocate(pixels * 4);
    const Image texture = procedural_tissue(size.width, size.height, 1);
    backend->upload(tissue.data(), texture.rgba.data(), tissue.bytes());
    const std::vector<float> host_tables = optics_tables();
    tables = backend->allocate(host_tables.size() * sizeof(float));
    backend->upload(tables.data(), host_tables.data(), tables.bytes());
  }
  void spread() { backend->run("spread", spread_work); }
  void blend() {
    backend->run("blend", blend_work(scene, tables.as<const float>(), tissue.as<const std::uint8_t>(),
                                     stain.as<const float>(), nullptr, nullptr, frame.as<std::uint8_t>()));
  }
};

void time_stage(benchmark::State& state, BackendKind kind, const Size& size,
                const std::function<void(StageScene&)>& work) {
  std::unique_ptr<Backend> backend = backend_or_skip(kind, state);
  if (!backend) return;
  StageScene scene(std::move(backend), size);
  for (int i = 0; i < kWarmUpRuns; ++i) work(scene);
  double total_ms = 0.0;
  for (auto _ : state) {
    const double ms = scene.backend->time_ms([&] { work(scene); });
    state.SetIterationTime(ms / 1000.0);
    total_ms += ms;
  }
  const double ms = total_ms / double(state.iterations());
  state.counters["ms"] = ms;
  state.counters["frame_budget_%"] = 100.0 * ms / kFrameBudgetMs;
  state.counters["Mpixel/s"] = double(size.width) * size.height / (ms * 1e3);
  state.SetLabel(scene.backend->device_name());
}

void register_all() {
  const std::pair<const char*, std::function<void(StageScene&)>> stages[] = {
      {"spread", [](StageScene& s) { s.spread(); }},
      {"blend", [](StageScene& s) { s.blend(); }},
      {"spread+blend", [](StageScene& s) { s.spread(); s.blend(); }}};
  for (const BackendKind kind : {BackendKind::cpu, BackendKind::cuda})
    for (const auto& [stage, work] : stages)
      for (const Size& size : kSizes) {
        const std::string name = std::string(to_string(kind)) + "/" + stage + "/" + size.name;
        benchmark::RegisterBenchmark(name.c_str(), [kind, size, work = work](benchmark::State& state) {
          time_stage(state, kind, size, work);
        })
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Repetitions(5)
            ->ReportAggregatesOnly(true)
            ->DisplayAggregatesOnly(true);
      }
}

}  // namespace
}  // namespace bleedsim

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  bleedsim::register_all();
  bleedsim::register_particle_benchmarks();
  bleedsim::register_frame_benchmarks();
  bleedsim::register_haptic_benchmarks();
  bleedsim::register_spread_benchmarks();
  bleedsim::register_live_loop_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  bleedsim::release_particle_benchmarks();
  bleedsim::release_frame_benchmarks();
  benchmark::Shutdown();
  return 0;
}
