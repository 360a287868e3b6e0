#pragma once
// What the benchmarks in this folder share: the warm-up convention, the backend (or a visible skip
// where CUDA cannot run), and the benchmark groups that main() registers.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>

#include "core/runtime/backend.h"

namespace bleedsim {

constexpr int kWarmUpRuns = 3;

// The backend to measure, or null after marking the benchmark skipped with the reason (a build
// without CUDA, a machine without a device): the run goes on and the table says why.
inline std::unique_ptr<Backend> backend_or_skip(BackendKind kind, benchmark::State& state) {
  if (kind == BackendKind::cpu) return make_cpu_backend(0);
  std::string why_not;
  if (!cuda_device_available(&why_not)) {
    state.SkipWithError(("CUDA not measured: " + why_not).c_str());
    return nullptr;
  }
  return make_cuda_backend();
}

// scenarios/<name>.toml, from the repository root where the benchmark runs there, else from the
// source tree it was built from.
inline std::string scenario_path(const std::string& name) {
  const std::string here = "scenarios/" + name + ".toml";
  return std::filesystem::exists(here) ? here : std::string(BLEEDSIM_SOURCE_DIR) + "/" + here;
}

// bench/particle_bench.cpp: the particle step in the settled-pile state. The piles it settles are
// kept between benchmarks of one size; release them before main() returns, while the CUDA runtime
// is still up.
void register_particle_benchmarks();
void release_particle_benchmarks();

// bench/frame_bench.cpp: the screen-space frame (spread, splat, blur passes, blend) over a pile of
// particles. Its scene is kept between the benchmarks of one size; released as the piles are.
void register_frame_benchmarks();
void release_frame_benchmarks();

// bench/haptic_bench.cpp: the haptic tick, and a trace-driven run's tick and frame percentiles.
void register_haptic_benchmarks();

// bench/spread_bench.cpp: a frame's spread against the number of cuts made, most of them settled.
void register_spread_benchmarks();

// bench/live_loop_bench.cpp: the 1 kHz loop on its own thread, idle and beside a simulation.
void register_live_loop_benchmarks();

}  // namespace bleedsim
