#pragma once
// The scene's cuts as a scenario writes them ([[cut]]): their table, and what a cut leaves out,
// which comes from the scene's [spread] (the stain's size) and [particles] (the wound's flow).
#include "core/runtime/params.h"
#include "core/scene/scene.h"

namespace bleedsim {

// A cut at (x, y) starting at t with the scene's spread and particle defaults.
Cut cut_at(const Scene& scene, double x_mm, double y_mm, double start_s);

// The [[cut]] tables; a cut's key in messages is "cut[i]".
const ParamTable<Cut>& cut_table();

}  // namespace bleedsim
