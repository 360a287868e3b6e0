#include "core/effects/trail_stage.h"

#include <cmath>
#include <vector>

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

void TrailStage::run(const Scene&, State&, Backend& backend) { launch(backend, work_); }

}  // namespace bleedsim
