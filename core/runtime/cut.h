#pragma once
// A cut made by the tool: where and when, how large a wound (the spread stain's radius and growth
// rate) and how hard it bleeds particles (rate, for how long). What a scenario's [[cut]] leaves
// out comes from the scene's [spread] and [particles] defaults (Scene::cut_at).
#include "core/runtime/params.h"

namespace bleedsim {

struct Cut {
  double x_mm = 0.0;
  double y_mm = 0.0;
  double start_s = 0.0;
  double radius_mm = 0.0;
  double growth_per_s = 0.0;
  double rate_per_s = 0.0;  // particles per second while it bleeds
  double bleed_s = 0.0;     // how long it bleeds particles
};

// The [[cut]] tables; a cut's key in messages is "cut[i]".
const ParamTable<Cut>& cut_table();

}  // namespace bleedsim
