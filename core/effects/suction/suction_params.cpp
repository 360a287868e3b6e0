#include "core/effects/suction/suction_params.h"

#include "core/effects/contact/contact_params.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/tips.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

ParamProblem suction_acts(const SuctionParams&, const Scene& scene) {
  return needs_blood_and_instrument("radius_mm", scene);
}

// The blood the tip's body parts is held just outside it: the suction must reach past it.
ParamProblem reaches_past_the_tip(const SuctionParams& s, const Scene& scene) {
  const ContactParams* contact = scene.effects.find<ContactParams>();
  const ParticleParams* particles = scene.effects.find<ParticleParams>();
  if (!contact || !particles) return {};
  const double body_mm = tip_body_mm(*contact, *particles);
  if (s.radius_mm > body_mm) return {};
  return {"radius_mm", "must be larger than contact.tip_radius_mm + the particles' radius, " + format_number(body_mm) +
                           " mm: the blood the tip parts lies just outside its body, "
                           "and the suction must reach it (got " +
                           format_number(s.radius_mm) + ")"};
}

// At most kMaxParticleRate particles a second: a step's quota stays well inside 32 bits.
ParamProblem quota_countable(const SuctionParams& s, const Scene& scene) {
  const ParticleParams* particles = scene.effects.find<ParticleParams>();
  if (!particles) return {};
  const double rate = s.max_flow_mm3_per_s / particles->particle_volume_mm3;
  if (rate <= kMaxParticleRate) return {};
  return {"max_flow_mm3_per_s", "takes up to " + format_number(rate) +
                                    " particles per second (max_flow_mm3_per_s / particles.particle_volume_mm3); "
                                    "at most " +
                                    format_number(kMaxParticleRate)};
}

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

}  // namespace bleedsim
