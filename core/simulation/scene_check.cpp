#include "core/simulation/scene_check.h"

#include <string>
#include <vector>

#include "core/effects/cuts.h"
#include "core/effects/effect_list.h"
#include "core/effects/tips.h"
#include "core/haptics/haptic_params.h"

namespace bleedsim {
namespace {

// Each element of `items` against `table`, named "cut[i]" or "tip[i]".
template <class P>
ParamProblem each_problem(const ParamTable<P>& table, const std::vector<P>& items, const Scene& scene) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (ParamProblem problem =
            check_params(table, items[i], scene, std::string(table.name) + "[" + std::to_string(i) + "]"))
      return problem;
  return {};
}

// The vessel density map a scene with [vessels] bleeds by: one value per pixel, each 0 … 1.
ParamProblem vessel_map_problem(const Scene& scene) {
  if (!scene.effects.has<VesselParams>()) return {};
  if (Count(scene.vessel_density.size()) != scene.domain.pixels())
    return {"vessels", "its density map must hold width_px × height_px values"};
  for (const float v : scene.vessel_density)
    if (!(v >= 0.0f && v <= 1.0f)) return {"vessels", "its density map's values must lie between 0 and 1"};
  return {};
}

}  // namespace

ParamProblem scene_problem(const Scene& scene) {
  if (ParamProblem problem = check_params(scene_table(), scene, scene)) return problem;
  const Domain& d = scene.domain;
  if (scene.tissue.width != d.width_px || scene.tissue.height != d.height_px ||
      Count(scene.tissue.rgba.size()) != d.pixels() * 4)
    return {"tissue", "must be a width_px × height_px RGBA8 image"};
  if (ParamProblem problem = each_problem(cut_table(), scene.cuts, scene)) return problem;
  if (ParamProblem problem = effects_problem(scene)) return problem;
  if (ParamProblem problem = vessel_map_problem(scene)) return problem;
  if (ParamProblem problem = each_problem(tip_table(), scene.tips, scene)) return problem;
  if (ParamProblem problem = tip_path_problem(scene)) return problem;
  if (scene.haptics)
    if (ParamProblem problem = check_params(haptic_table(), *scene.haptics, scene)) return problem;
  if (scene.trace && (!scene.haptics || scene.trace->samples.empty()))
    return {"haptics", "a scene's trace needs [haptics] to replay it through, and samples"};
  return {};
}

}  // namespace bleedsim
