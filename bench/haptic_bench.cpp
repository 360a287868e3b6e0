// The haptic loop against its 1 ms budget, and real scenes' frames against both budgets.
//
// haptic/tick: HapticLoop ticks (the replayed sample, contact, force, cut) over the default
// synthesised stroke (bleedsim trace synth's defaults, 4,101 ticks); the counters give the mean
// per tick over every stroke Google Benchmark runs.
//
// Scene/<backend>/<scene>: a real scene from its first frame to its last, once per repetition:
// scenarios/default.toml (three cuts bleeding, no stylus) and scenarios/falcon-stroke.toml (a recorded
// stroke cutting the 640 × 480 panel). Every frame (its haptic ticks, its stages and the frame's copy
// to the host, so the device's work is done) and every haptic tick is timed with the wall clock, as
// `bleedsim run` does. Counters: their p50, p99 and max, and p99 as a share of the 33.3 ms and 1 ms
// budgets (ticks only where the scene has a stylus). Run from the repository root (or with the
// scenarios' folder at BLEEDSIM_SOURCE_DIR, as built).
#include <chrono>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/effects/spread/spread_params.h"
#include "core/haptics/haptics.h"
#include "core/haptics/trace_replay.h"
#include "core/io/scenario.h"
#include "core/io/trace_csv.h"
#include "core/io/trace_synth.h"
#include "core/runtime/timing_summary.h"
#include "core/simulation/simulation.h"

namespace bleedsim {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void time_tick(benchmark::State& state) {
  const Trace trace = parse_trace(synthesize_trace(SynthSpec{}), "synthesised");
  const std::int64_t ticks = std::int64_t(trace.samples.size());
  Scene scene;  // the loop needs the panel and the contact: a 32 × 24 mm panel, default stylus
  scene.domain = Domain{640, 480, 32.0, 24.0};
  scene.effects.set(SpreadParams{});
  HapticParams stylus;
  stylus.origin_x_mm = 16.0;
  stylus.origin_y_mm = 12.0;
  scene.haptics = stylus;
  // An iteration is the whole stroke, a fresh loop each time; the counters are per tick.
  double total_s = 0;
  for (auto _ : state) {
    HapticLoop loop(scene);
    const Clock::time_point start = Clock::now();
    for (std::int64_t n = 0; n < ticks; ++n) benchmark::DoNotOptimize(loop.tick(trace_sample_at_tick(trace, n)));
    const double elapsed_s = seconds_since(start);
    state.SetIterationTime(elapsed_s);
    total_s += elapsed_s;
  }
  const double per_tick_s = total_s / double(state.iterations()) / double(ticks);
  state.counters["tick_us"] = 1e6 * per_tick_s;
  state.counters["haptic_budget_%"] = 100.0 * per_tick_s / kHapticBudget_s;
}

void time_run(benchmark::State& state, BackendKind kind, const std::string& name) {
  if (!backend_or_skip(kind, state)) return;
  const Scenario scenario = load_scenario(scenario_path(name));
  const Scene& scene = scenario.scene;
  std::vector<double> frames, ticks;
  for (auto _ : state) {
    Simulation sim(scene, BackendChoice{kind == BackendKind::cuda ? BackendChoice::Want::cuda : BackendChoice::Want::cpu, 0});
    std::vector<std::uint8_t> rgba(sim.field("frame").field->bytes());
    const Clock::time_point run_start = Clock::now();
    for (int k = 0; k < scene.frame_count(); ++k) {
      const Clock::time_point start = Clock::now();
      sim.step();
      sim.copy_field("frame", rgba.data());  // the host has the frame: the GPU's work is done
      frames.push_back(seconds_since(start));
      ticks.insert(ticks.end(), sim.haptic_tick_seconds().begin(), sim.haptic_tick_seconds().end());
    }
    state.SetIterationTime(seconds_since(run_start));
    state.SetLabel(sim.backend().device_name());
  }
  const Percentiles f = percentiles_of(frames);
  state.counters["frame_p50_ms"] = 1e3 * f.p50;
  state.counters["frame_p99_ms"] = 1e3 * f.p99;
  state.counters["frame_max_ms"] = 1e3 * f.max;
  state.counters["frame_p99_budget_%"] = 100.0 * f.p99 / kFrameBudget_s;
  if (ticks.empty()) return;
  const Percentiles t = percentiles_of(ticks);
  state.counters["tick_p50_us"] = 1e6 * t.p50;
  state.counters["tick_p99_us"] = 1e6 * t.p99;
  state.counters["tick_max_us"] = 1e6 * t.max;
  state.counters["tick_p99_budget_%"] = 100.0 * t.p99 / kHapticBudget_s;
}

}  // namespace

void register_haptic_benchmarks() {
  benchmark::RegisterBenchmark("haptic/tick", time_tick)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Repetitions(5)
      ->ReportAggregatesOnly(true)
      ->DisplayAggregatesOnly(true);
  for (const char* scene : {"default", "falcon-stroke"})
    for (const BackendKind kind : {BackendKind::cpu, BackendKind::cuda})
      benchmark::RegisterBenchmark((std::string("Scene/") + to_string(kind) + "/" + scene).c_str(),
                                   [kind, scene](benchmark::State& state) { time_run(state, kind, scene); })
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1)
          ->Repetitions(3)
          ->ReportAggregatesOnly(true)
          ->DisplayAggregatesOnly(true);
}

}  // namespace bleedsim
