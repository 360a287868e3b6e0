#include "core/haptics/realtime_priority.h"

#include <pthread.h>
#include <sched.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace bleedsim {

int set_fifo_for_this_thread(int priority) {
  sched_param param{};
  param.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
}

ThreadPriority request_fifo_priority(int priority, int (*set_fifo)(int)) {
  const int lowest = sched_get_priority_min(SCHED_FIFO), highest = sched_get_priority_max(SCHED_FIFO);
  const std::string asked = "SCHED_FIFO " + std::to_string(priority);
  if (priority < lowest || priority > highest)
    throw std::invalid_argument(asked + ": expected a priority from " + std::to_string(lowest) + " to " +
                                std::to_string(highest));
  ThreadPriority got;
  const int error = set_fifo(priority);
  if (error == 0) {
    got.fifo = true;
    got.priority = priority;
    got.text = asked;
    return got;
  }
  got.text = "normal priority: " + asked + " was refused (error " + std::to_string(error) + ", " +
             std::strerror(error) + ")";
  if (error == EPERM)
    got.text += ": it needs CAP_SYS_NICE or an RLIMIT_RTPRIO of at least " + std::to_string(priority) +
                " (ulimit -r), which containers seldom grant";
  return got;
}

}  // namespace bleedsim
