#pragma once
// The [haptics] table of the stylus (core/scene/stylus.h), and what passivity at 1 kHz asks of it
// (docs/haptics.md; docs/scenario-format.md, [haptics]).
#include "core/runtime/params.h"
#include "core/scene/stylus.h"

namespace bleedsim {

// The [haptics] table. Its keys trace and repair_gap_ms say where a file's trace is and how it is
// read (core/io/scenario.cpp); a host that drives the stylus itself has neither.
const ParamTable<HapticParams>& haptic_table();

// What passivity at 1 kHz asks of the device's own damping (Colgate & Schenkel: a virtual spring k
// and damper b sampled every T are passive when b_device > k·T/2 + |b|): k·T/2 + |b|, in N·s/m.
double passivity_demand_Ns_per_m(const HapticParams& params);

// The edge of the Z-width at 1 kHz (the stiffness–damping region rendered passively; Colgate & Schenkel,
// docs/haptics.md "Z-width"): the largest |b| a spring k renders passively with the device's damping
// B, B − k·T/2. Below zero no damping is passive: the spring alone asks more than B (k > 2B/T).
double passive_damping_limit_Ns_per_m(double stiffness_N_per_m, double device_damping_Ns_per_m);

// Why these contact parameters cannot be rendered passively at 1 kHz, blaming stiffness_N_per_m
// or damping_Ns_per_m; none when they can.
ParamProblem passivity_problem(const HapticParams& params);

}  // namespace bleedsim
