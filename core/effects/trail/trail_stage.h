#pragma once
// The trails where blood ran (docs/optics.md): what the trail stage (trail_stage.cpp, with the
// trail's row) makes of its parameters and of the suction's path.
#include <vector>

#include "core/effects/trail/trail_params.h"
#include "core/physics/trail.h"

namespace bleedsim {

// One frame's drying: exp(−1 / (frame rate · drying_s)), in double, rounded once.
float trail_decay_per_frame(const TrailParams& trail, double frame_rate_hz);

// Points the trail at the suction's path this frame: the first `count` segments of `segments` (the
// host's copy of what `on_backend` holds), within `reach_mm`, and their bounds.
void sweep_trail(TrailPixel& work, const float* on_backend, const std::vector<float>& segments, int count,
                 double reach_mm);

}  // namespace bleedsim
