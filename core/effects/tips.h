#pragma once
// The instrument the suction and the tip's contact act through (docs/bleeding.md, "The
// instrument"): the stylus ([haptics]: its trace's samples, or a host's), or in a scene without
// one a scripted path of [[tip]] points; the path's table and rules, and where its tip is.
#include <optional>
#include <string>
#include <vector>

#include "core/runtime/params.h"
#include "core/scene/scene.h"
#include "core/scene/state.h"

namespace bleedsim {

// The [[tip]] tables; a point's key in messages is "tip[i]".
const ParamTable<TipPoint>& tip_table();

// What is wrong with a scene's path as a whole (its points one by one are tip_table()'s): fewer
// than two points, times not increasing, a path beside the stylus, a path nothing uses. Blames
// the point at fault ("tip[3].t_s"), or "tip".
ParamProblem tip_path_problem(const Scene& scene);

// What acts through the instrument needs particles to act on, and an instrument: a rule of the
// tables of what does, blaming `key`.
ParamProblem needs_blood_and_instrument(const char* key, const Scene& scene);

// The tip of the scene's instrument at t: its scripted path (`path`, scripted_tool(scene.tips)),
// which ends at its last point, or the stylus (State::stylus), which stays where it was last seen.
std::optional<ToolSample> instrument_at(const Scene& scene, const std::vector<ToolSample>& path, const State& state,
                                        double t_s);

// The instrument in words, for `bleedsim validate`: "the stylus", or the scripted tip's points and times.
std::string instrument_words(const Scene& scene);

}  // namespace bleedsim
