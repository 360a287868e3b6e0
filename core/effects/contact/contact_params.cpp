#include "core/effects/contact/contact_params.h"

#include <algorithm>

#include "core/effects/tips.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

ParamProblem contact_acts(const ContactParams&, const Scene& scene) {
  return needs_blood_and_instrument("tip_radius_mm", scene);
}

// Wherever the tip is, a particle pushed out of it has somewhere on the panel to go: the body is
// narrower than the box the particles' centres keep to.
ParamProblem body_fits_the_panel(const ContactParams& c, const Scene& scene) {
  const ParticleParams* particles = scene.effects.find<ParticleParams>();
  if (!particles) return {};
  const double body_mm = tip_body_mm(c, *particles);
  const double box_mm = std::min(scene.domain.width_mm, scene.domain.height_mm) - particles->diameter_mm;
  if (2.0 * body_mm < box_mm) return {};
  return {"tip_radius_mm", "is too large for the panel: the tip's body, " + format_number(2.0 * body_mm) +
                               " mm across with a particle's radius each side, must be narrower than the " +
                               format_number(box_mm) + " mm the particles' centres keep to"};
}

}  // namespace

double tip_body_mm(const ContactParams& contact, const ParticleParams& particles) {
  return contact.tip_radius_mm + particles.diameter_mm / 2.0;
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

}  // namespace bleedsim
