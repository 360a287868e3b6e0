#pragma once
// Scenes built in code, as a host simulator embedding bleedsim would build them.
#include "core/effects/cuts.h"
#include "core/effects/spread/spread_params.h"
#include "core/runtime/tissue.h"
#include "core/scene/scene.h"

namespace bleedsim::test {

// 64 × 48 px over 16 × 12 mm (0.25 mm pixels), 1 s at 30 Hz; with or without the spread.
inline Scene scene_in_code(bool with_spread) {
  Scene scene;
  scene.name = with_spread ? "in-code-spread" : "in-code-tissue";
  scene.domain = Domain{64, 48, 16.0, 12.0};
  scene.duration_s = 1.0;
  scene.frame_rate_hz = 30.0;
  scene.tissue = procedural_tissue(64, 48, 5);
  scene.tissue_source = "procedural";
  if (with_spread) scene.effects.set(SpreadParams{3.0, 1.5});
  scene.cuts.push_back(cut_at(scene, 8.125, 6.125, 0.0));  // the centre of pixel (32, 24)
  return scene;
}

}  // namespace bleedsim::test
