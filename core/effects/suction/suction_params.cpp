#include "core/effects/suction/suction_params.h"

#include <algorithm>
#include <string>

#include "core/runtime/message_text.h"
#include "core/scene/scene.h"

namespace bleedsim {
namespace {

// What acts through the instrument needs particles to act on, and an instrument.
ParamProblem needs_blood_and_instrument(const char* key, const Scene& scene) {
  if (!scene.particles) return {key, "has no effect: this scene declares no [particles]"};
  if (!scene.haptics && scene.tips.empty())
    return {key, "has no instrument to act through: declare [haptics] (the stylus) or a scripted path of "
                 "[[tip]] points"};
  return {};
}

double particle_radius_mm(const Scene& scene) { return scene.particles->diameter_mm / 2.0; }

ParamProblem suction_acts(const SuctionParams&, const Scene& scene) {
  return needs_blood_and_instrument("radius_mm", scene);
}

// The blood the tip's body parts is held just outside it: the suction must reach past it.
ParamProblem reaches_past_the_tip(const SuctionParams& s, const Scene& scene) {
  if (!scene.contact || !scene.particles) return {};
  const double body_mm = scene.contact->tip_radius_mm + particle_radius_mm(scene);
  if (s.radius_mm > body_mm) return {};
  return {"radius_mm", "must be larger than contact.tip_radius_mm + the particles' radius, " +
                           format_number(body_mm) + " mm: the blood the tip parts lies just outside its body, "
                           "and the suction must reach it (got " + format_number(s.radius_mm) + ")"};
}

// At most kMaxParticleRate particles a second: a step's quota stays well inside 32 bits.
ParamProblem quota_countable(const SuctionParams& s, const Scene& scene) {
  if (!scene.particles) return {};
  const double rate = s.max_flow_mm3_per_s / scene.particles->particle_volume_mm3;
  if (rate <= kMaxParticleRate) return {};
  return {"max_flow_mm3_per_s", "takes up to " + format_number(rate) +
                                    " particles per second (max_flow_mm3_per_s / particles.particle_volume_mm3); "
                                    "at most " + format_number(kMaxParticleRate)};
}

ParamProblem contact_acts(const ContactParams&, const Scene& scene) {
  return needs_blood_and_instrument("tip_radius_mm", scene);
}

// Wherever the tip is, a particle pushed out of it has somewhere on the panel to go: the body is
// narrower than the box the particles' centres keep to.
ParamProblem body_fits_the_panel(const ContactParams& c, const Scene& scene) {
  if (!scene.particles) return {};
  const double r = particle_radius_mm(scene), body_mm = c.tip_radius_mm + r;
  const double box_mm = std::min(scene.domain.width_mm, scene.domain.height_mm) - 2.0 * r;
  if (2.0 * body_mm < box_mm) return {};
  return {"tip_radius_mm", "is too large for the panel: the tip's body, " + format_number(2.0 * body_mm) +
                               " mm across with a particle's radius each side, must be narrower than the " +
                               format_number(box_mm) + " mm the particles' centres keep to"};
}

// Any finite position: a scripted tip may pass beyond the panel.
const Range kAnywhere{-1e4, 1e4};

}  // namespace

const ParamTable<SuctionParams>& suction_table() {
  using P = SuctionParams;
  using T = ParamType;
  static const ParamTable<P> table{
      "suction",
      "declares suction at the instrument's tip: it takes the blood within its reach, nearest first, up to its "
      "flow (needs [particles], and [haptics] or [[tip]])",
      {{"radius_mm", T::number, BLEEDSIM_MEMBER(P, radius_mm), "mm", {0, 1e4, true},
        "its reach: particles whose centres lie this close to the tip are taken"},
       {"max_flow_mm3_per_s", T::number, BLEEDSIM_MEMBER(P, max_flow_mm3_per_s), "mm³/s", {0, 1e6},
        "the most blood it takes a second, whole particles at a time"},
       {"buttons", T::integer, BLEEDSIM_MEMBER(P, buttons), "", {1, 15},
        "with the stylus ([haptics]): the grip buttons (a bitmask) that turn it on while the tip is in contact"}},
      {{"the scene has [particles], and an instrument: [haptics] or [[tip]]", suction_acts},
       {"with [contact], radius_mm is larger than contact.tip_radius_mm + the particles' radius",
        reaches_past_the_tip},
       {"max_flow_mm3_per_s / particles.particle_volume_mm3 is at most 1e8 particles a second", quota_countable}}};
  return table;
}

const ParamTable<ContactParams>& contact_table() {
  using P = ContactParams;
  static const ParamTable<P> table{
      "contact",
      "declares the instrument's tip a body in the blood: particles part around it and close behind it (needs "
      "[particles], and [haptics] or [[tip]])",
      {{"tip_radius_mm", ParamType::number, BLEEDSIM_MEMBER(P, tip_radius_mm), "mm", {0, 1e4, true},
        "the tip's radius on the panel: no particle's centre comes nearer than this plus its own radius"}},
      {{"the scene has [particles], and an instrument: [haptics] or [[tip]]", contact_acts},
       {"the tip's body, with a particle's radius each side, is narrower than the panel less a particle's "
        "diameter",
        body_fits_the_panel}}};
  return table;
}

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
  if (!scene.suction && !scene.contact)
    return {"tip", "has no effect: a path drives [suction] or [contact], and this scene declares neither"};
  if (tips.size() < 2) return {"tip", "a path needs at least two points (when it starts and when it ends)"};
  for (std::size_t i = 1; i < tips.size(); ++i)
    if (!(tips[i].t_s > tips[i - 1].t_s))
      return {"tip[" + std::to_string(i) + "].t_s",
              "must be later than the point before it (" + format_number(tips[i - 1].t_s) + " s; got " +
                  format_number(tips[i].t_s) + ")"};
  return {};
}

}  // namespace bleedsim
