#pragma once
#include <cstddef>
#include <vector>

#include "core/effects/stage.h"
#include "core/physics/trail.h"

namespace bleedsim {

// (splat/thickness, the suction's path) => trail/residue
// Each frame, in scenes with [trail]: the residue of the blood that ran over each pixel, drying,
// and none where the suction passed. The stage readies the frame's pass (the suction's path) and
// leaves it in State for the blend, which runs it in its own pass over the pixels (TrailThenBlend).
class TrailStage final : public Stage {
 public:
  TrailStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  TrailPixel work_{};
  Buffer sweep_;  // the suction's path this frame, uploaded; grows with it
};

// One frame's drying: exp(−1 / (frame rate · drying_s)), in double, rounded once.
float trail_decay_per_frame(const TrailParams& trail, double frame_rate_hz);

// Points the trail at the suction's path this frame: the first `count` segments of `segments` (the
// host's copy of what `on_backend` holds), within `reach_mm`, and their bounds.
void sweep_trail(TrailPixel& work, const float* on_backend, const std::vector<float>& segments, int count,
                 double reach_mm);

}  // namespace bleedsim
