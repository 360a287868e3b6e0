#pragma once
// The 1 kHz loop on wall time (docs/haptics.md, "The live loop under load"): tick n is due at
// start + n·T, in integer nanoseconds of CLOCK_MONOTONIC, and the thread sleeps to that absolute
// deadline rather than for a period, so neither the ticks' compute nor a late wake-up moves the
// ticks after it.
#include <cstdint>
#include <functional>
#include <vector>

namespace bleedsim {

// T, the haptic period (kHapticPeriod_s), in nanoseconds.
constexpr std::int64_t kHapticPeriod_ns = 1'000'000;

// When tick n is due: start + n·T exactly, however long the loop has run.
std::int64_t tick_deadline_ns(std::int64_t start_ns, std::int64_t n);

// The clock a loop runs on: the OS's, or a test's.
class TickClock {
 public:
  virtual ~TickClock() = default;
  virtual std::int64_t now_ns() = 0;
  // Returns at or after deadline_ns (at once when it has passed).
  virtual void sleep_until_ns(std::int64_t deadline_ns) = 0;
};

// CLOCK_MONOTONIC, slept on with clock_nanosleep(TIMER_ABSTIME).
TickClock& monotonic_tick_clock();

// When one tick was due, began and ended, in the clock's nanoseconds.
struct TickTimes {
  std::int64_t deadline_ns = 0;
  std::int64_t start_ns = 0;
  std::int64_t end_ns = 0;
};

// Runs tick(n) for n = 0 … count − 1, tick n at its deadline from the first's (the clock's time on
// entry). A late tick runs at once and none is skipped: after a stall the loop catches up with its
// schedule. Each tick's times are kept in memory allocated before the first tick.
std::vector<TickTimes> run_ticks(TickClock& clock, std::int64_t count, const std::function<void(std::int64_t)>& tick);

}  // namespace bleedsim
