// Real-time priority for the live loop (core/haptics/realtime_priority.h): granted, or refused with
// a message and the thread left at normal priority; never an error, except a priority out of range.
#include <gtest/gtest.h>

#include <cerrno>
#include <stdexcept>
#include <string>

#include "core/haptics/realtime_priority.h"

namespace bleedsim {
namespace {

int asked_for = 0;
int grant(int priority) {
  asked_for = priority;
  return 0;
}
int refuse_as_a_container_does(int) { return EPERM; }
int refuse_for_lack_of_resources(int) { return EAGAIN; }

TEST(RealtimePriority, GrantedItIsSchedFifoAtThePriorityAskedFor) {
  const ThreadPriority got = request_fifo_priority(kHapticFifoPriority, grant);
  EXPECT_EQ(asked_for, 80);
  EXPECT_TRUE(got.fifo);
  EXPECT_EQ(got.priority, 80);
  EXPECT_EQ(got.text, "SCHED_FIFO 80");
}

TEST(RealtimePriority, RefusedTheLoopRunsAtNormalPriorityAndSaysWhy) {
  const ThreadPriority eperm = request_fifo_priority(80, refuse_as_a_container_does);
  EXPECT_FALSE(eperm.fifo);
  EXPECT_EQ(eperm.priority, 0);
  EXPECT_EQ(eperm.text,
            "normal priority: SCHED_FIFO 80 was refused (error 1, Operation not permitted): it needs CAP_SYS_NICE or an "
            "RLIMIT_RTPRIO of at least 80 (ulimit -r), which containers seldom grant");
  const ThreadPriority eagain = request_fifo_priority(80, refuse_for_lack_of_resources);
  EXPECT_FALSE(eagain.fifo);
  EXPECT_EQ(eagain.text, "normal priority: SCHED_FIFO 80 was refused (error 11, Resource temporarily unavailable)");
}

TEST(RealtimePriority, APriorityOutsideSchedFifosRangeIsNotAsked) {
  asked_for = 0;
  for (const int priority : {0, 100}) {
    try {
      request_fifo_priority(priority, grant);
      FAIL() << "priority " << priority << " was asked for";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "SCHED_FIFO " + std::to_string(priority) + ": expected a priority from 1 to 99");
    }
  }
  EXPECT_EQ(asked_for, 0);
}

}  // namespace
}  // namespace bleedsim
