#pragma once
// A recorded trace played back as the haptic loop's device (docs/haptics.md, "Replaying a trace").
#include <cstdint>

#include "core/haptics/haptics.h"
#include "core/scene/trace.h"

namespace bleedsim {

// The device sample of haptic tick n: the trace at t = first sample's time + n / 1 kHz. The
// recorder's clock need not meet the ticks, so the position is interpolated linearly between the
// samples either side; the buttons are those of the sample at or before. Past its last sample the
// stylus stays where the trace left it.
DeviceSample trace_sample_at_tick(const Trace& trace, std::int64_t tick);

}  // namespace bleedsim
