#pragma once
// How a cut bleeds over time (docs/bleeding.md): the blood its wound has given, and how fast it
// leaves. The rules a scene adds ([pulse]: a heartbeat; [vessels]: a cut's vessel density, set
// when it is made) reach here as plain values, so this module knows no effect above it.
#include "core/bleeding/heartbeat.h"
#include "core/scene/cut.h"

namespace bleedsim {

// The blood a cut's wound has given by time t (mm³): flow × wound × vessel density over the part of
// [start, start + bleed] before t, falling as exp(−s/clot_s) when it clots, and, for an arterial
// wound in a scene with a heartbeat, beating with it (pulse_waveform). `beat` may be null.
double cut_blood_mm3(const Cut& cut, double t_s, const Heartbeat* beat);

// The speed of the blood leaving the wound at time t relative to the scene's emission velocity: a
// fixed opening, so speed follows flow, w(t) for an arterial wound with a heartbeat, else 1.
double cut_exit_speed_scale(const Cut& cut, double t_s, const Heartbeat* beat);

}  // namespace bleedsim
