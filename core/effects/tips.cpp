#include "core/effects/tips.h"

#include "core/effects/effect_list.h"
#include "core/effects/particles/particle_params.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// Any finite position: a scripted tip may pass beyond the panel.
const Range kAnywhere{-1e4, 1e4};

// "[suction] or [contact]": what a path may drive, from the list of effects.
std::string hooks_in_words() {
  const std::vector<std::string> tables = hook_tables();
  std::string words;
  for (std::size_t i = 0; i < tables.size(); ++i)
    words += (i == 0 ? "" : i + 1 == tables.size() ? " or " : ", ") + ("[" + tables[i] + "]");
  return words;
}

}  // namespace

const ParamTable<TipPoint>& tip_table() {
  using P = TipPoint;
  using T = ParamType;
  static const ParamTable<P> table{
      "tip",
      "one table per point of a scripted instrument's path (in a scene without [haptics]): its tip is in contact "
      "from the first point's time to the last's, moving in straight lines between points",
      {{"t_s", T::number, BLEEDSIM_MEMBER(P, t_s), "s", {0, 86400}, "when the tip is here", nullptr, true},
       {"x_mm", T::number, BLEEDSIM_MEMBER(P, x_mm), "mm", kAnywhere,
        "from the panel's left edge; beyond the panel, it acts on what its reach covers of it", nullptr, true},
       {"y_mm", T::number, BLEEDSIM_MEMBER(P, y_mm), "mm", kAnywhere, "from the panel's top edge (y down)", nullptr,
        true}},
      {}};
  return table;
}

ParamProblem tip_path_problem(const Scene& scene) {
  const std::vector<TipPoint>& tips = scene.tips;
  if (tips.empty()) return {};
  if (scene.haptics)
    return {"tip", "a scene has one instrument: its stylus ([haptics]) or a scripted path of [[tip]] points, not both"};
  if (!declares_a_hook(scene))
    return {"tip", "has no effect: a path drives " + hooks_in_words() + ", and this scene declares " +
                       (hook_tables().size() == 2 ? "neither" : "none of them")};
  if (tips.size() < 2) return {"tip", "a path needs at least two points (when it starts and when it ends)"};
  for (std::size_t i = 1; i < tips.size(); ++i)
    if (!(tips[i].t_s > tips[i - 1].t_s))
      return {"tip[" + std::to_string(i) + "].t_s", "must be later than the point before it (" +
                                                        format_number(tips[i - 1].t_s) + " s; got " +
                                                        format_number(tips[i].t_s) + ")"};
  return {};
}

ParamProblem needs_blood_and_instrument(const char* key, const Scene& scene) {
  if (!scene.effects.has<ParticleParams>()) return {key, "has no effect: this scene declares no [particles]"};
  if (!scene.haptics && scene.tips.empty())
    return {key,
            "has no instrument to act through: declare [haptics] (the stylus) or a scripted path of "
            "[[tip]] points"};
  return {};
}

std::optional<ToolSample> instrument_at(const Scene& scene, const std::vector<ToolSample>& path, const State& state,
                                        double t_s) {
  return scene.tips.empty() ? tool_at(state.stylus, t_s, true) : tool_at(path, t_s, false);
}

std::string instrument_words(const Scene& scene) {
  if (scene.tips.empty()) return "the stylus";
  return "a scripted tip, " + std::to_string(scene.tips.size()) + " points from " +
         format_number(scene.tips.front().t_s) + " s to " + format_number(scene.tips.back().t_s) + " s";
}

}  // namespace bleedsim
