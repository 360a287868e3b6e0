#include "core/effects/trail/trail_stage.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/effects/suction/suction_hook.h"
#include "core/physics/pixel_kernels.h"

namespace bleedsim {

float trail_decay_per_frame(const TrailParams& trail, double frame_rate_hz) {
  return static_cast<float>(std::exp(-1.0 / (frame_rate_hz * trail.drying_s)));
}

void sweep_trail(TrailPixel& work, const float* on_backend, const std::vector<float>& segments, int count,
                 double reach_mm) {
  work.sweep = on_backend;
  work.sweep_segments = count;
  work.reach_sq = float(reach_mm * reach_mm);
  double low[2] = {HUGE_VAL, HUGE_VAL}, high[2] = {-HUGE_VAL, -HUGE_VAL};
  for (int k = 0; k < 4 * count; ++k) {
    low[k % 2] = std::min(low[k % 2], double(segments[k]));
    high[k % 2] = std::max(high[k % 2], double(segments[k]));
  }
  // Grown by the reach and a margin far beyond float32's rounding of a distance there (a few units
  // in the last place of the coordinates): the bounds only skip pixels no segment reaches.
  const double margin = reach_mm + 1e-3 + 1e-4 * (reach_mm + std::max({std::fabs(low[0]), std::fabs(low[1]),
                                                                          std::fabs(high[0]), std::fabs(high[1])}));
  for (int a = 0; a < 2; ++a) {
    work.sweep_box[a] = float(low[a] - margin);
    work.sweep_box[2 + a] = float(high[a] + margin);
  }
}

TrailStage::TrailStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend) : Stage(kind) {
  const Field& film = input(scene, state, "splat/thickness");
  Field& residue = add_field(scene, state, backend, "trail/residue");
  const std::vector<float> dry(scene.domain.pixels().to<std::size_t>(), 0.0f);
  backend.upload(residue.data.data(), dry.data(), dry.size() * sizeof(float));
  work_ = TrailPixel{film.data.as<const float>(), residue.data.as<float>(), float(scene.trail->residue),
                     trail_decay_per_frame(*scene.trail, scene.frame_rate_hz), scene.domain.grid()};
}

MemoryParts TrailStage::memory_for(const Scene& scene) { return {scene.domain.memory(sizeof(float))}; }

void TrailStage::run(const Scene& scene, State& state, Backend& backend) {
  if (scene.suction) {
    const std::vector<float> sweep =
        suction_sweep(scene, state, double(state.frames_done) / scene.frame_rate_hz, scene.frame_time_s(state.frames_done));
    const std::size_t bytes = sweep.size() * sizeof(float);
    if (bytes > sweep_.bytes()) sweep_ = allocate(backend, 2 * bytes);
    if (bytes > 0) backend.upload(sweep_.data(), sweep.data(), bytes);
    sweep_trail(work_, sweep_.as<const float>(), sweep, int(sweep.size() / 4), scene.suction->radius_mm);
  }
  // Run by the blend, in its pass: it reads the residue at its own pixel only, after this.
  state.trail_pass = work_;
}

}  // namespace bleedsim
