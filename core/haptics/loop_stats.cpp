#include "core/haptics/loop_stats.h"

#include <cstddef>
#include <utility>

namespace bleedsim {
namespace {

double seconds(std::int64_t ns) { return double(ns) / 1e9; }

}  // namespace

LoopStats loop_stats(const std::vector<TickTimes>& times) {
  LoopStats stats;
  stats.ticks = std::int64_t(times.size());
  std::vector<double> period, compute, late;
  for (std::size_t n = 0; n < times.size(); ++n) {
    const TickTimes& t = times[n];
    if (n > 0) period.push_back(seconds(t.start_ns - times[n - 1].start_ns));
    compute.push_back(seconds(t.end_ns - t.start_ns));
    late.push_back(seconds(t.start_ns - t.deadline_ns));
    if (t.end_ns > t.deadline_ns + kHapticPeriod_ns) ++stats.missed;
  }
  stats.period = percentiles_of(std::move(period));
  stats.compute = percentiles_of(std::move(compute));
  stats.late = percentiles_of(std::move(late));
  return stats;
}

}  // namespace bleedsim
