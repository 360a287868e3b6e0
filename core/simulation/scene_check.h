#pragma once
// The check of a whole scene, built in code or read from a file, against every table it holds.
#include "core/runtime/params.h"
#include "core/scene/scene.h"

namespace bleedsim {

// The first problem of a scene: the scene's own table, the tissue's size, each cut's table, each
// declared effect's (core/effects/effect_list.h), the vessel map's size, each point of a scripted
// path and the path as a whole, the stylus' table, a trace without [haptics].
ParamProblem scene_problem(const Scene& scene);

}  // namespace bleedsim
