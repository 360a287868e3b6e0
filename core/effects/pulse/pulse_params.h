#pragma once
// A heartbeat for arterial wounds (docs/bleeding.md, "Pulse"): a rule for how a cut bleeds. Its
// waveform and the blood it gives are core/bleeding/heartbeat.h; which wounds are arterial is the
// cut's (Cut::arterial), or with [vessels] their vessel density's (vessel_params.h).
#include "core/bleeding/heartbeat.h"
#include "core/runtime/params.h"

namespace bleedsim {

template <class P>
struct Effect;

// Present in a Scene only when the scene calls for a pulse; needs [particles].
struct PulseParams : Heartbeat {
  double arterial_density = 0.5;  // with [vessels]: a wound this dense along its length is arterial
};

const ParamTable<PulseParams>& pulse_table();
const Effect<PulseParams>& pulse_effect();

}  // namespace bleedsim
