// The spread's cost against the cuts made (issue 17): the falcon-stroke scene's panel, 640 × 480 px
// over 32 × 24 mm, with N cuts whose stains are full (settled in the first frame) and a stroke going
// on: a cut a frame, each full after ten frames, so that ten are growing and one settles each frame.
// A frame — the spread and the blend, the stain copied to the host so the device's work is done —
// should cost the same whatever N (issue 17's acceptance: within ±10 % of N = 10 up to 10,000).
// The N settled cuts lie in one 8 × 6 mm patch, which ten already cover, so that the stained area,
// which the blend's cost follows (a bare pixel is drawn quicker), is the same for every N; the
// stroke runs over the rest of the panel.
#include <chrono>
#include <random>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/effects/cuts.h"
#include "core/effects/spread/spread_params.h"
#include "core/runtime/tissue.h"
#include "core/simulation/simulation.h"

namespace bleedsim {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kWarmFrames = 15;   // the stroke's ten growing cuts in place
constexpr int kTimedFrames = 60;  // frames timed per repetition
constexpr double kFrameRate = 30.0;

Scene scene_with_cuts(int settled) {
  Scene scene;
  scene.name = "spread-cuts";
  scene.domain = Domain{640, 480, 32.0, 24.0};
  scene.frame_rate_hz = kFrameRate;
  scene.duration_s = (kWarmFrames + kTimedFrames + 2) / kFrameRate;
  scene.tissue = procedural_tissue(640, 480, 1);
  scene.tissue_source = "procedural";
  scene.effects.set(SpreadParams{2.0, kFrameRate / 10.0});  // full ten frames after its cut
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> patch_x(1.0, 9.0), patch_y(1.0, 7.0), x(12.0, 31.0), y(1.0, 23.0);
  for (int c = 0; c < settled; ++c) {
    Cut cut = cut_at(scene, patch_x(random), patch_y(random), 0.0);
    cut.growth_per_s = 1000.0;  // full by the first frame's time, 1/30 s
    scene.cuts.push_back(cut);
  }
  for (int f = 0; f < kWarmFrames + kTimedFrames + 1; ++f) scene.cuts.push_back(cut_at(scene, x(random), y(random), f / kFrameRate));
  return scene;
}

void time_frames(benchmark::State& state, BackendKind kind, int settled) {
  if (!backend_or_skip(kind, state)) return;
  const Scene scene = scene_with_cuts(settled);
  Simulation sim(scene, BackendChoice{kind == BackendKind::cuda ? BackendChoice::Want::cuda : BackendChoice::Want::cpu, 0});
  std::vector<std::uint8_t> stain(sim.field("spread/stain").field->bytes());
  for (int k = 0; k < kWarmFrames; ++k) sim.step();
  for (auto _ : state) {
    const Clock::time_point start = Clock::now();
    sim.step();
    sim.copy_field("spread/stain", stain.data());
    state.SetIterationTime(std::chrono::duration<double>(Clock::now() - start).count());
  }
  state.SetLabel(sim.backend().device_name());
  state.counters["cuts"] = double(settled + kWarmFrames + kTimedFrames + 1);
}

}  // namespace

void register_spread_benchmarks() {
  for (const BackendKind kind : {BackendKind::cpu, BackendKind::cuda})
    for (const int settled : {10, 100, 1000, 10000})
      benchmark::RegisterBenchmark(
          (std::string("Spread/") + to_string(kind) + "/settled_cuts:" + std::to_string(settled)).c_str(),
          [kind, settled](benchmark::State& state) { time_frames(state, kind, settled); })
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(kTimedFrames)
          ->Repetitions(5)
          ->ReportAggregatesOnly(true);
}

}  // namespace bleedsim
