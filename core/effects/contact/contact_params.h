#pragma once
// The tip's body in the blood (docs/bleeding.md, "Contact"): a disc of the instrument's tip that the
// particles part around and close behind. A hook in the particle step (contact_hook.h).
#include "core/effects/particles/particle_params.h"
#include "core/runtime/params.h"

namespace bleedsim {

template <class P>
struct Effect;

// Present in a Scene only when the instrument's tip parts the blood; needs [particles] and an instrument.
struct ContactParams {
  double tip_radius_mm = 1.0;  // the tip's body on the panel: a disc no particle enters
};

const ParamTable<ContactParams>& contact_table();
const Effect<ContactParams>& contact_effect();

// How near the tip a particle's centre may come: the tip's radius and a particle's.
double tip_body_mm(const ContactParams& contact, const ParticleParams& particles);

}  // namespace bleedsim
