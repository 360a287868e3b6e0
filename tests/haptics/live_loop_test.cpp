// The live loop's schedule (docs/haptics.md, "The live loop under load"): tick n is due at
// start + n·T in integer nanoseconds, whatever the ticks cost and however late the thread wakes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/haptics/live_loop.h"

namespace bleedsim {
namespace {

TEST(LiveLoopSchedule, TheNthDeadlineIsTheStartPlusNPeriodsExactly) {
  // A start as CLOCK_MONOTONIC gives it after 34 hours up; 3.6e9 ticks are 1,000 hours at 1 kHz,
  // 3.6e15 ns after it. Summing 1e-3 s as a double 3.6e9 times would end 0.19 s late.
  const std::int64_t start = 123'456'789'012'345;
  EXPECT_EQ(tick_deadline_ns(start, 0), 123'456'789'012'345);
  EXPECT_EQ(tick_deadline_ns(start, 1), 123'456'790'012'345);
  EXPECT_EQ(tick_deadline_ns(start, 3'600'000'000), 3'723'456'789'012'345);
}

// A clock that wakes 70 µs after the deadline (or after now, when it has passed), and whose time the
// ticks advance by what they cost; it records the deadlines slept to.
class ScriptedClock final : public TickClock {
 public:
  std::int64_t now_ns() override { return now; }
  void sleep_until_ns(std::int64_t deadline_ns) override {
    slept_to.push_back(deadline_ns);
    now = std::max(now, deadline_ns) + 70'000;
  }
  std::int64_t now = 5'000;
  std::vector<std::int64_t> slept_to;
};

TEST(LiveLoopSchedule, LateWakeUpsAndAStallDoNotMoveTheDeadlinesAfterThem) {
  // Every tick costs 300 µs, tick 3 2.8 ms (a stall). The start is the clock on entry, 5,000 ns.
  // Tick 3 starts at 3,075,000 and ends at 5,875,000; ticks 4–6 run at once (each woken 70 µs
  // after its call), and tick 7 is back on its schedule. Deadlines: 5,000 + n·1,000,000.
  ScriptedClock clock;
  const std::vector<TickTimes> times = run_ticks(clock, 8, [&](std::int64_t n) { clock.now += n == 3 ? 2'800'000 : 300'000; });
  const std::vector<std::int64_t> deadlines = {5'000,     1'005'000, 2'005'000, 3'005'000,
                                               4'005'000, 5'005'000, 6'005'000, 7'005'000};
  const std::vector<std::int64_t> starts = {75'000,    1'075'000, 2'075'000, 3'075'000,
                                            5'945'000, 6'315'000, 6'685'000, 7'075'000};
  const std::vector<std::int64_t> ends = {375'000,   1'375'000, 2'375'000, 5'875'000,
                                          6'245'000, 6'615'000, 6'985'000, 7'375'000};
  EXPECT_EQ(clock.slept_to, deadlines);
  ASSERT_EQ(times.size(), 8u);
  for (std::size_t n = 0; n < times.size(); ++n) {
    EXPECT_EQ(times[n].deadline_ns, deadlines[n]) << "tick " << n;
    EXPECT_EQ(times[n].start_ns, starts[n]) << "tick " << n;
    EXPECT_EQ(times[n].end_ns, ends[n]) << "tick " << n;
  }
}

TEST(LiveLoopSchedule, ANegativeCountIsRefused) {
  ScriptedClock clock;
  try {
    run_ticks(clock, -1, [](std::int64_t) {});
    FAIL() << "a negative count was run";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "a loop of -1 ticks: expected 0 or more");
  }
  EXPECT_TRUE(run_ticks(clock, 0, [](std::int64_t) {}).empty());
}

}  // namespace
}  // namespace bleedsim
