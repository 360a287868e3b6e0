#include "core/effects/trail_stage.h"

#include <cmath>
#include <vector>

#include "core/effects/instrument.h"
#include "core/physics/pixel_kernels.h"

namespace bleedsim {

float trail_decay_per_frame(const TrailParams& trail, double frame_rate_hz) {
  return static_cast<float>(std::exp(-1.0 / (frame_rate_hz * trail.drying_s)));
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
    work_.sweep = sweep_.as<const float>();
    work_.sweep_segments = int(sweep.size() / 4);
    work_.reach_sq = float(scene.suction->radius_mm * scene.suction->radius_mm);
  }
  launch(backend, work_);
}

}  // namespace bleedsim
