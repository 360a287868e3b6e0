#pragma once
// Trails (docs/optics.md, "Trails"): where blood has run, the tissue stays wetted and faintly stained.
#include "core/runtime/params.h"

namespace bleedsim {

template <class P>
struct Effect;

// Present in a Scene only when the scene calls for trails; needs [particles].
struct TrailParams {
  double residue = 0.1;     // of the film that passes, left behind as an equivalent film
  double drying_s = 20.0;   // the residue's time constant
};

const ParamTable<TrailParams>& trail_table();
// Its row: the trail stage (trail_stage.cpp).
const Effect<TrailParams>& trail_effect();

}  // namespace bleedsim
