// The screen-space frame against the 30 Hz frame budget (33.3 ms), stage by stage: the spread, the
// splat, each pass of the blur (downsample, horizontal, vertical, upsample) and the four together,
// the blend, and the whole frame (spread + splat + the four blur passes + blend); and the endoscope's
// view: the trail, the blend lit by the headlight with highlights over the residue too, and the whole
// lit frame (the frame's stages, then the trail and the lit blend in one pass, as the stages run
// them); the trail also where the suction swept the panel (a stylus's path over one frame, a
// segment a haptic tick). On CUDA at 1920×1080 and
// 3840×2160 with 1,048,576 particles; on the CPU reference at 1920×1080 with 65,536.
//
// The particles are input only (no physics runs): N particles of the default 0.2 mm diameter on a
// hexagonal lattice at the bottom of the panel, touching, all alive (age 0, a lifetime as long as a scene may ask),
// built on the host and uploaded once. The panel is sized so that they fill its lower 28 %: it is
// 16:9, 480 × 270 mm for 1,048,576 particles (⌊W/d − ½⌋ = 2,399 per row, 438 rows, a pile 75.9 mm
// high), scaled by √(N / 2²⁰) for other N (120 × 67.5 mm at 65,536: 599 per row, 110 rows). Its
// pixels follow from the panel: 0.25 mm/px at 1920×1080 and 0.125 mm/px at 3840×2160 for 1,048,576
// (the same scene, drawn finer), 0.0625 mm/px at 1920×1080 for 65,536. Splat radius = the diameter
// (the default), blur defaults (downsample 2, radius 4, sigma 2), and eight half-grown spread cuts
// placed over the panel as stage_bench places them. docs/benchmarks.md ("The frame") has the rest.
//
// One scene per backend, size and N, kept between that group's cases (a static cache, released
// before main() returns). Before each case one whole frame runs untimed, so every pass reads what
// the pass before it wrote; then three warm-up runs and kIterations timed runs per repetition
// (Backend::time_ms: CUDA events around the launches, the CPU's wall clock), five repetitions.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/effects/blend/blend_stage.h"
#include "core/effects/blend/optics_params.h"
#include "core/effects/blur/blur_params.h"
#include "core/effects/blur/blur_stage.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/particles/splat_stage.h"
#include "core/effects/spread/spread_tiles.h"
#include "core/effects/suction/suction_hook.h"
#include "core/effects/suction/suction_params.h"
#include "core/effects/trail/trail_params.h"
#include "core/effects/trail/trail_stage.h"
#include "core/haptics/haptic_params.h"
#include "core/physics/optics_tables.h"
#include "core/physics/pixel_kernels.h"
#include "core/runtime/backend.h"
#include "core/runtime/tissue.h"
#include "core/scene/scene.h"

namespace bleedsim {
namespace {

constexpr double kFrameBudgetMs = 1000.0 / 30.0;
constexpr int kIterations = 20;  // timed runs per repetition
constexpr int kRepetitions = 5;
constexpr int kCutCount = 8;
// The panel for 2²⁰ particles of the default diameter; other N scale it by √(N / 2²⁰).
constexpr double kPanelWidthMm = 480.0, kPanelHeightMm = 270.0;
constexpr double kReferenceParticles = 1048576.0;
constexpr double kSweepSpeed = 20.0;  // mm/s: the suction's tip, sideways through the pile
// The trail's swept cases: a segment (a scripted path's frame, between two of its points) and a
// stylus's frame at 30 Hz (a segment a haptic tick, 1 kHz: 34 in the first frame).
constexpr int kSweeps[] = {1, 34};

enum class Work { spread, splat, downsample, horizontal, vertical, upsample, blur, blend, frame, trail, blend_lit, frame_lit };

const char* name_of(Work work) {
  switch (work) {
    case Work::spread: return "spread";
    case Work::splat: return "splat";
    case Work::downsample: return "blur_downsample";
    case Work::horizontal: return "blur_horizontal";
    case Work::vertical: return "blur_vertical";
    case Work::upsample: return "blur_upsample";
    case Work::blur: return "blur";
    case Work::blend: return "blend";
    case Work::frame: return "frame";
    case Work::trail: return "trail";
    case Work::blend_lit: return "blend_lit";
    case Work::frame_lit: return "frame_lit";
  }
  return "?";
}

struct Size {
  const char* name;
  int width, height;
};
constexpr Size k1080p{"1920x1080", 1920, 1080}, k2160p{"3840x2160", 3840, 2160};

// The scene: default particles (capacity N, nothing expires), default blur, the panel for N.
Scene frame_scene(const Size& size, int n) {
  Scene scene;
  scene.name = "settled pile, one frame (bench/frame_bench.cpp)";
  scene.seed = 1;
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().capacity = n;
  scene.effects.set(BlurParams{});
  const double scale = std::sqrt(double(n) / kReferenceParticles);
  scene.domain.width_px = size.width;
  scene.domain.height_px = size.height;
  scene.domain.width_mm = kPanelWidthMm * scale;
  scene.domain.height_mm = kPanelHeightMm * scale;
  // Every particle alive and unfaded: a day (the most a scene may ask), or 1e9 steps.
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  const double steps_per_s = resolve_particles(p, scene).steps_per_s;
  scene.effects.get<ParticleParams>().lifetime_s = std::min(86400.0, 1.0e9 / steps_per_s);
  return scene;
}

// One frame's inputs and buffers on one backend.
struct FrameScene {
  std::unique_ptr<Backend> backend;
  Size size;
  int n;
  Scene scene;
  std::string problem;  // why it cannot be measured (empty when it can)
  int columns = 0, rows = 0;
  double pile_height_mm = 0.0;
  std::uint64_t deposits = 0;  // pixel deposits the splat makes per frame
  double film_max_mm = 0.0;    // the blurred film after one frame: its thickest pixel ...
  double film_share = 0.0;     // ... and the share of the panel it covers

  Buffer position, age, units, stamps, film, weights, low, across, blurred, cuts, stain, tissue, tables, residue, frame_rgba,
      sweep, fixed_light;
  std::vector<float> segments;  // the suction's path over one frame, as uploaded to `sweep`
  double reach_mm = 0.0;        // the suction's radius
  SpreadPixel spread_work{};
  SplatArgs splat_args{};
  BlurArgs blur_args{};
  TrailPixel trail_work{};
  BlendPixel blend_work{}, lit_blend_work{};

  FrameScene(std::unique_ptr<Backend> b, const Size& s, int count)
      : backend(std::move(b)), size(s), n(count), scene(frame_scene(s, count)) {
    problem = check_params(particle_table(), scene.effects.get<ParticleParams>(), scene).message;
    if (!problem.empty()) return;
    const PixelGrid grid = scene.domain.grid();
    const std::size_t pixels = std::size_t(grid.width) * grid.height;

    // The pile: slot s in row s / columns (row 0 at the bottom), spacing one diameter, age 0.
    // Even rows start one radius from the left edge, odd rows one diameter.
    const double d = scene.effects.get<ParticleParams>().diameter_mm, r = d / 2.0, row_mm = std::sqrt(3.0) / 2.0 * d;
    columns = int(std::floor(scene.domain.width_mm / d - 0.5 + 1e-9));
    rows = (n + columns - 1) / columns;
    pile_height_mm = (rows - 1) * row_mm + d;
    std::vector<float> xy(2 * std::size_t(n));
    for (int slot = 0; slot < n; ++slot) {
      const int row = slot / columns, column = slot % columns;
      xy[2 * slot] = float(r + column * d + (row % 2 ? r : 0.0));
      xy[2 * slot + 1] = float(scene.domain.height_mm - r - row * row_mm);
    }
    const std::vector<std::uint32_t> ages(n, 0u);
    position = backend->allocate(xy.size() * sizeof(float));
    age = backend->allocate(ages.size() * sizeof(std::uint32_t));
    backend->upload(position.data(), xy.data(), position.bytes());
    backend->upload(age.data(), ages.data(), age.bytes());

    // The splat, as SplatStage sets it up.
    units = backend->allocate(pixels * sizeof(std::uint64_t));
    film = backend->allocate(pixels * sizeof(float));
    splat_args.lifetime = resolve_particles(scene).lifetime;
    splat_args.splat = make_splat_model(scene.effects.get<ParticleParams>(), scene.domain);
    splat_args.capacity = n;
    splat_args.grid = grid;
    splat_args.units = units.as<std::uint64_t>();
    splat_args.thickness_mm = film.as<float>();
    const std::vector<std::uint32_t> unstamped(splat_tile_count(grid), 0u);
    stamps = backend->allocate(unstamped.size() * sizeof(std::uint32_t));
    backend->upload(stamps.data(), unstamped.data(), stamps.bytes());
    backend->upload(units.data(), std::vector<std::uint64_t>(pixels, 0u).data(), units.bytes());
    splat_args.tiles = {stamps.as<std::uint32_t>(), splat_tiles_across(grid), 0u};
    {  // Its deposits, counted on the host from the same positions.
      SplatArgs host = splat_args;
      host.position = xy.data();
      host.age = ages.data();
      for (int slot = 0; slot < n; ++slot)
        splat_particle(host, slot, [&](std::size_t, std::uint64_t) { ++deposits; }, [](int) {});
    }
    splat_args.position = position.as<const float>();
    splat_args.age = age.as<const std::uint32_t>();

    // The blur, as BlurStage sets it up.
    const BlurParams& bp = scene.effects.get<BlurParams>();
    const std::vector<float> taps = gaussian_weights(bp.radius_px, bp.sigma_px);
    weights = backend->allocate(taps.size() * sizeof(float));
    backend->upload(weights.data(), taps.data(), weights.bytes());
    blur_args.width = grid.width;
    blur_args.height = grid.height;
    blur_args.factor = bp.downsample;
    blur_args.low_width = (grid.width + bp.downsample - 1) / bp.downsample;
    blur_args.low_height = (grid.height + bp.downsample - 1) / bp.downsample;
    blur_args.radius = bp.radius_px;
    const std::size_t low_pixels = std::size_t(blur_args.low_width) * blur_args.low_height;
    low = backend->allocate(low_pixels * sizeof(float));
    across = backend->allocate(low_pixels * sizeof(float));
    blurred = backend->allocate(pixels * sizeof(float));
    blur_args.weights = weights.as<const float>();
    blur_args.film = film.as<const float>();
    blur_args.low = low.as<float>();
    blur_args.across = across.as<float>();
    blur_args.blurred = blurred.as<float>();

    // The spread: eight half-grown stains over the panel, overlapping in pairs (stage_bench's).
    const float w_mm = float(scene.domain.width_mm), h_mm = float(scene.domain.height_mm);
    std::vector<SpreadCut> host_cuts;
    for (int c = 0; c < kCutCount; ++c)
      host_cuts.push_back({w_mm * (0.15f + 0.1f * c), h_mm * (c % 2 ? 0.4f : 0.6f), 0.15f * h_mm, 0.5f});
    SpreadUpload upload;  // the cuts and their tile table, as the spread stage uploads them
    upload.lay_out(host_cuts, 0, grid, spread_reach_per_mm(scene));
    cuts = backend->allocate(upload.bytes().size());
    backend->upload(cuts.data(), upload.bytes().data(), cuts.bytes());
    stain = backend->allocate(pixels * sizeof(float));
    spread_work = upload.pixel_work(cuts.data(), stain.as<float>());

    // The blend, as BlendStage runs it in a scene with a blurred film: stain and blur/thickness
    // over the procedural tissue, in linear light; lit, in a scene with [optics] and [trail], also
    // the residue, the headlight's falloff and the highlights. The trail as TrailStage runs it.
    tissue = backend->allocate(pixels * 4);
    const Image texture = procedural_tissue(grid.width, grid.height, 1);
    backend->upload(tissue.data(), texture.rgba.data(), tissue.bytes());
    const std::vector<float> host_tables = optics_tables();
    tables = backend->allocate(host_tables.size() * sizeof(float));
    backend->upload(tables.data(), host_tables.data(), tables.bytes());
    residue = backend->allocate(pixels * sizeof(float));
    const std::vector<float> dry(pixels, 0.0f);
    backend->upload(residue.data(), dry.data(), residue.bytes());
    frame_rgba = backend->allocate(pixels * 4);
    blend_work = bleedsim::blend_work(scene, tables.as<const float>(), tissue.as<const std::uint8_t>(), stain.as<const float>(),
                       blurred.as<const float>(), nullptr, frame_rgba.as<std::uint8_t>());
    Scene lit = scene;
    lit.effects.set(OpticsParams{});
    lit.effects.set(TrailParams{});
    fixed_light = backend->allocate(fixed_light_bytes(lit));
    make_fixed_light(lit, *backend, "blend", fixed_light.as<float>());
    lit_blend_work = bleedsim::blend_work(lit, tables.as<const float>(), tissue.as<const std::uint8_t>(), stain.as<const float>(),
                           blurred.as<const float>(), residue.as<const float>(), frame_rgba.as<std::uint8_t>(),
                           fixed_light.as<const float>());
    trail_work = {film.as<const float>(), residue.as<float>(), float(lit.effects.get<TrailParams>().residue),
                  trail_decay_per_frame(lit.effects.get<TrailParams>(), lit.frame_rate_hz), grid};

    // The suction's sweep, for the trail's swept cases: the stylus's samples over the first frame,
    // one a haptic tick, its tip moving sideways through the middle of the pile with the suction
    // on; suction_sweep() makes of them the segments the trail stage dries (34 at 30 Hz).
    Scene sucking = lit;
    sucking.effects.set(SuctionParams{});
    State stylus;
    const double frame_s = 1.0 / scene.frame_rate_hz;
    for (int tick = 0; tick <= int(std::ceil(frame_s / kHapticPeriod_s)); ++tick) {
      const double t_s = tick * kHapticPeriod_s;
      stylus.stylus.push_back({t_s, scene.domain.width_mm / 2.0 + kSweepSpeed * t_s,
                               scene.domain.height_mm - pile_height_mm / 2.0, true, kEveryButton});
    }
    segments = suction_sweep(sucking, stylus, 0.0, frame_s);
    sweep = backend->allocate(segments.size() * sizeof(float));
    backend->upload(sweep.data(), segments.data(), sweep.bytes());
    reach_mm = sucking.effects.get<SuctionParams>().radius_mm;

    // One frame, to see that the film is there.
    frame();
    std::vector<float> result(pixels);
    backend->download(result.data(), blurred.data(), blurred.bytes());
    std::size_t covered = 0;
    for (const float v : result) {
      film_max_mm = std::max(film_max_mm, double(v));
      covered += v > 0.0f;
    }
    film_share = double(covered) / double(pixels);
  }

  void spread() { backend->run("spread", spread_work); }
  // Each a frame: its stamp follows the last one's, as the splat stage's does.
  void splat() {
    ++splat_args.tiles.now;
    backend->run("splat", splat_args);
  }
  template <class Pass>
  void blur(const Pass& pass) { backend->run("blur", pass); }
  void blur() { blur_passes(blur_args).each([&](const auto& pass) { blur(pass); }); }
  // The splat, then the blur, as the stages run them in a frame: the blur's downsample in the
  // splat's conversion pass, then the blur's other three passes.
  void splat_and_blur() {
    ++splat_args.tiles.now;
    SplatArgs with_downsample = splat_args;
    with_downsample.downsample = blur_args;
    backend->run_shared({"splat", "blur"}, with_downsample);
    blur_passes(blur_args).each([&](const auto& pass) { blur(pass); }, false);
  }
  void blend() { backend->run("blend", blend_work); }
  void frame() {
    spread();
    splat_and_blur();
    blend();
  }
  void trail() { backend->run("trail", trail_work); }
  // The trail in the lit blend's pass, as the blend stage runs it.
  void frame_lit() {
    spread();
    splat_and_blur();
    backend->run_shared({"trail", "blend"}, pair_pixels(trail_work, lit_blend_work));
  }
  void run(Work work) {
    switch (work) {
      case Work::spread: spread(); break;
      case Work::splat: splat(); break;
      case Work::downsample: blur(blur_passes(blur_args).downsample); break;
      case Work::horizontal: blur(blur_passes(blur_args).horizontal); break;
      case Work::vertical: blur(blur_passes(blur_args).vertical); break;
      case Work::upsample: blur(blur_passes(blur_args).upsample); break;
      case Work::blur: blur(); break;
      case Work::blend: blend(); break;
      case Work::frame: frame(); break;
      case Work::trail: trail(); break;
      case Work::blend_lit: backend->run("blend", lit_blend_work); break;
      case Work::frame_lit: frame_lit(); break;
    }
  }
};

// One scene at a time: the cases of a backend, size and N run one after another and share it.
std::unique_ptr<FrameScene>& cached_scene() {
  static std::unique_ptr<FrameScene> scene;
  return scene;
}

FrameScene* scene_or_skip(BackendKind kind, const Size& size, int n, benchmark::State& state) {
  std::unique_ptr<FrameScene>& scene = cached_scene();
  if (scene && scene->backend->kind() == kind && scene->size.width == size.width &&
      scene->size.height == size.height && scene->n == n)
    return scene.get();
  scene.reset();
  std::unique_ptr<Backend> backend = backend_or_skip(kind, state);
  if (!backend) return nullptr;
  scene = std::make_unique<FrameScene>(std::move(backend), size, n);
  return scene.get();
}

// `sweep`: the trail dries where the suction swept this frame, along the first `sweep` segments
// of the stylus's path (0: nowhere).
void time_frame(benchmark::State& state, BackendKind kind, const Size& size, int n, Work work, int sweep) {
  try {
    FrameScene* scene = scene_or_skip(kind, size, n, state);
    if (!scene) return;
    if (!scene->problem.empty()) {
      state.SkipWithError(("frame not measured: " + scene->problem).c_str());
      return;
    }
    sweep_trail(scene->trail_work, scene->sweep.as<const float>(), scene->segments,
                std::min(sweep, int(scene->segments.size() / 4)), scene->reach_mm);
    scene->frame();  // every buffer holds what a frame leaves in it
    for (int i = 0; i < kWarmUpRuns; ++i) scene->run(work);
    double total_ms = 0.0;
    for (auto _ : state) {
      const double ms = scene->backend->time_ms([&] { scene->run(work); });
      state.SetIterationTime(ms / 1000.0);
      total_ms += ms;
    }
    scene->backend->synchronize();
    const double ms = total_ms / double(state.iterations());
    state.counters["ms"] = ms;
    state.counters["frame_budget_%"] = 100.0 * ms / kFrameBudgetMs;
    // Throughput in what the work is made of: particles for the splat, the pixels it writes
    // otherwise (the downsampled grid's for the downsample and the two Gaussian passes).
    const double panel = double(size.width) * size.height;
    const double low = double(scene->blur_args.low_width) * scene->blur_args.low_height;
    switch (work) {
      case Work::splat:
        state.counters["Mparticle/s"] = double(n) / (ms * 1e3);
        state.counters["deposits/particle"] = double(scene->deposits) / n;
        break;
      case Work::downsample:
      case Work::horizontal:
      case Work::vertical: state.counters["Mpixel/s"] = low / (ms * 1e3); break;
      case Work::frame:
      case Work::frame_lit:
        state.counters["Mpixel/s"] = panel / (ms * 1e3);
        state.counters["Mparticle/s"] = double(n) / (ms * 1e3);
        state.counters["film_max_mm"] = scene->film_max_mm;
        state.counters["film_%"] = 100.0 * scene->film_share;
        break;
      default: state.counters["Mpixel/s"] = panel / (ms * 1e3); break;
    }
    if (sweep > 0) state.counters["sweep_segments"] = scene->trail_work.sweep_segments;
    char scale[32];
    std::snprintf(scale, sizeof scale, "%g mm/px", double(scene->scene.domain.grid().mm_per_px_x));
    state.SetLabel(scene->backend->device_name() + ", " + scale);
  } catch (const std::exception& e) {
    state.SkipWithError((std::string("frame not measured: ") + e.what()).c_str());
  }
}

void register_case(BackendKind kind, const Size& size, int n, Work work, int sweep = 0) {
  const std::string name = std::string("Frame/") + to_string(kind) + "/" + name_of(work) + "/" + size.name + "/" +
                           std::to_string(n) + (sweep > 0 ? "/sweep_segments:" + std::to_string(sweep) : "");
  benchmark::RegisterBenchmark(name.c_str(), [kind, size, n, work, sweep](benchmark::State& state) {
    time_frame(state, kind, size, n, work, sweep);
  })
      ->UseManualTime()
      ->Iterations(kIterations)
      ->Unit(benchmark::kMillisecond)
      ->Repetitions(kRepetitions)
      ->ReportAggregatesOnly(true)
      ->DisplayAggregatesOnly(true);
}

}  // namespace

void register_frame_benchmarks() {
  // Grouped by backend, size and N, so each scene is built once.
  const Work works[] = {Work::spread,   Work::splat,    Work::downsample, Work::horizontal,
                        Work::vertical, Work::upsample, Work::blur,       Work::blend,
                        Work::frame,    Work::trail,    Work::blend_lit,  Work::frame_lit};
  for (const Work work : works) register_case(BackendKind::cpu, k1080p, 65536, work);
  for (const int sweep : kSweeps) register_case(BackendKind::cpu, k1080p, 65536, Work::trail, sweep);
  for (const Size& size : {k1080p, k2160p}) {
    for (const Work work : works) register_case(BackendKind::cuda, size, 1048576, work);
    for (const int sweep : kSweeps) register_case(BackendKind::cuda, size, 1048576, Work::trail, sweep);
  }
}

void release_frame_benchmarks() { cached_scene().reset(); }

}  // namespace bleedsim
