#pragma once
// What a run of the live loop kept to (docs/haptics.md, "The live loop under load"): its ticks'
// periods, compute and lateness, and the deadlines it missed.
#include <cstdint>
#include <vector>

#include "core/haptics/live_loop.h"
#include "core/runtime/timing_summary.h"

namespace bleedsim {

struct LoopStats {
  std::int64_t ticks = 0;
  Percentiles period;   // from one tick's start to the next's: ticks − 1 of them, in seconds
  Percentiles compute;  // from a tick's start to its end
  Percentiles late;     // from a tick's deadline to its start
  // Ticks that ended after the next tick's deadline: the device held the force of the tick before
  // through a whole period. A stall of m periods misses m ticks.
  std::int64_t missed = 0;
  double missed_per_10k() const { return ticks == 0 ? 0.0 : 1e4 * double(missed) / double(ticks); }
};

LoopStats loop_stats(const std::vector<TickTimes>& times);

}  // namespace bleedsim
