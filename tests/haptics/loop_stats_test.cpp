// The live loop's statistics (core/haptics/loop_stats.h) on a sequence of tick times made by hand:
// 101 ticks due every 1 ms from 0, each starting 20 µs late and computing for 100 µs, except
//   tick 30: computes 980 µs, ending exactly on tick 31's deadline (not missed);
//   tick 31: computes 980,001 ns, ending 1 ns after tick 32's deadline (missed);
//   tick 50: starts 620 µs late and computes 500 µs (ends 120 µs past tick 51's deadline: missed);
//   tick 80: starts 220 µs late (ends well before tick 81's deadline);
//   tick 90: computes 1.1 ms (missed).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/haptics/loop_stats.h"

namespace bleedsim {
namespace {

std::vector<TickTimes> handmade_ticks() {
  std::vector<TickTimes> times;
  for (std::int64_t n = 0; n <= 100; ++n) {
    const std::int64_t late = n == 50 ? 620'000 : n == 80 ? 220'000 : 20'000;
    const std::int64_t compute = n == 30 ? 980'000 : n == 31 ? 980'001 : n == 50 ? 500'000 : n == 90 ? 1'100'000 : 100'000;
    const std::int64_t deadline = n * 1'000'000;
    times.push_back({deadline, deadline + late, deadline + late + compute});
  }
  return times;
}

TEST(LoopStats, PeriodsAreFromStartToStartWithNearestRankPercentiles) {
  // 100 periods of 1 ms + late_n − late_(n−1): 1.6 ms into tick 50 and 0.4 ms out of it, 1.2 ms
  // into tick 80 and 0.8 ms out of it, 96 of 1 ms. Sorted: 0.4, 0.8, 1.0 × 96, 1.2, 1.6; p50 the
  // 50th (1.0), p99 the 99th (1.2), max 1.6.
  const LoopStats stats = loop_stats(handmade_ticks());
  EXPECT_EQ(stats.ticks, 101);
  EXPECT_EQ(stats.period.count, 100u);
  EXPECT_EQ(stats.period.p50, 1.0e-3);
  EXPECT_EQ(stats.period.p99, 1.2e-3);
  EXPECT_EQ(stats.period.max, 1.6e-3);
}

TEST(LoopStats, ComputeAndLatenessPerTick) {
  // 101 computes: 100 µs × 97, 500 µs, 980 µs, 980.001 µs, 1.1 ms; p99 is the ⌈0.99 · 101⌉ = 100th,
  // 980.001 µs. Lateness: 20 µs × 99, 220 µs, 620 µs; the 100th is 220 µs.
  const LoopStats stats = loop_stats(handmade_ticks());
  EXPECT_EQ(stats.compute.count, 101u);
  EXPECT_EQ(stats.compute.p50, 100e-6);
  EXPECT_EQ(stats.compute.p99, 980.001e-6);
  EXPECT_EQ(stats.compute.max, 1.1e-3);
  EXPECT_EQ(stats.late.p50, 20e-6);
  EXPECT_EQ(stats.late.p99, 220e-6);
  EXPECT_EQ(stats.late.max, 620e-6);
}

TEST(LoopStats, ATickIsMissedWhenItEndsAfterTheNextDeadline) {
  // Ticks 31, 50 and 90 end after the next deadline; tick 30 ends on it. 3 of 101: 30,000/101 per
  // 10,000 ticks.
  const LoopStats stats = loop_stats(handmade_ticks());
  EXPECT_EQ(stats.missed, 3);
  EXPECT_DOUBLE_EQ(stats.missed_per_10k(), 30'000.0 / 101.0);
}

TEST(LoopStats, NoTicksAndOneTick) {
  const LoopStats none = loop_stats({});
  EXPECT_EQ(none.ticks, 0);
  EXPECT_EQ(none.missed_per_10k(), 0.0);
  // One tick has no period; it started 5 µs late and computed 2 µs.
  const LoopStats one = loop_stats({TickTimes{1'000, 6'000, 8'000}});
  EXPECT_EQ(one.period.count, 0u);
  EXPECT_EQ(one.compute.max, 2e-6);
  EXPECT_EQ(one.late.max, 5e-6);
  EXPECT_EQ(one.missed, 0);
}

}  // namespace
}  // namespace bleedsim
