#include "core/haptics/live_loop.h"

#include <time.h>

#include <cerrno>
#include <stdexcept>
#include <string>

namespace bleedsim {

std::int64_t tick_deadline_ns(std::int64_t start_ns, std::int64_t n) { return start_ns + n * kHapticPeriod_ns; }

namespace {

constexpr std::int64_t kNanosecondsPerSecond = 1'000'000'000;

class MonotonicClock final : public TickClock {
 public:
  std::int64_t now_ns() override {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    return std::int64_t(now.tv_sec) * kNanosecondsPerSecond + now.tv_nsec;
  }
  void sleep_until_ns(std::int64_t deadline_ns) override {
    const timespec until{time_t(deadline_ns / kNanosecondsPerSecond), long(deadline_ns % kNanosecondsPerSecond)};
    // A signal wakes the sleep early; the deadline is absolute, so sleeping again is exact.
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, nullptr) == EINTR) {
    }
  }
};

}  // namespace

TickClock& monotonic_tick_clock() {
  static MonotonicClock clock;
  return clock;
}

std::vector<TickTimes> run_ticks(TickClock& clock, std::int64_t count, const std::function<void(std::int64_t)>& tick) {
  if (count < 0) throw std::invalid_argument("a loop of " + std::to_string(count) + " ticks: expected 0 or more");
  // Written before the first tick, so that no tick meets a page fault the loop's own records cause.
  std::vector<TickTimes> times(std::size_t(count), TickTimes{});
  const std::int64_t start_ns = clock.now_ns();
  for (std::int64_t n = 0; n < count; ++n) {
    TickTimes& t = times[std::size_t(n)];
    t.deadline_ns = tick_deadline_ns(start_ns, n);
    clock.sleep_until_ns(t.deadline_ns);
    t.start_ns = clock.now_ns();
    tick(n);
    t.end_ns = clock.now_ns();
  }
  return times;
}

}  // namespace bleedsim
