#pragma once
// Real-time priority for the live loop's thread (docs/haptics.md, "The live loop under load"):
// SCHED_FIFO where the OS grants it; where it does not (EPERM without CAP_SYS_NICE or an
// RLIMIT_RTPRIO, as in most containers), the loop runs at normal priority and says so.
#include <string>

namespace bleedsim {

// The priority a haptic thread asks for: above any normal thread, below the kernel's own threads
// at 99 (migration, watchdogs), which must still preempt it.
constexpr int kHapticFifoPriority = 80;

// What the calling thread got.
struct ThreadPriority {
  bool fifo = false;  // SCHED_FIFO was granted
  int priority = 0;   // its SCHED_FIFO priority, when granted
  std::string text;   // "SCHED_FIFO 80", or "normal priority: ..." with the refusal and its reason
};

// Makes the calling thread SCHED_FIFO at `priority` (pthread_setschedparam): 0, or the errno.
int set_fifo_for_this_thread(int priority);

// Asks for SCHED_FIFO at `priority` through set_fifo (the OS's, unless a test gives its own). A
// refusal is not an error: the thread keeps its normal priority and the text says why. A priority
// outside SCHED_FIFO's range (1 … 99 on Linux) is refused before asking: std::invalid_argument.
ThreadPriority request_fifo_priority(int priority, int (*set_fifo)(int) = set_fifo_for_this_thread);

}  // namespace bleedsim
