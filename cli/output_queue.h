#pragma once
// A run's frames written on a thread of their own (issue 17: output off the critical path): the
// simulation hands over a copy of each frame's fields and goes on to the next while this one is
// deflated into HDF5 and encoded as PNG. Frames are written one at a time in the order they came,
// so the files are those a run writing them itself would make, byte for byte.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "core/haptics/haptics.h"

namespace bleedsim::cli {

// One frame's outputs: its fields as the host copied them, and the haptic ticks replayed for it.
struct FrameJob {
  long frame = 0;
  double time_s = 0.0;
  std::vector<std::vector<std::uint8_t>> fields;
  std::vector<HapticTick> ticks;
};

class OutputQueue {
 public:
  // `write` runs on the queue's thread, a job at a time; at most `capacity` jobs wait for it.
  OutputQueue(std::size_t capacity, std::function<void(const FrameJob&)> write);
  // Writes what is still queued, unless a write failed, and ends the thread.
  ~OutputQueue();
  OutputQueue(const OutputQueue&) = delete;
  OutputQueue& operator=(const OutputQueue&) = delete;

  // A job whose buffers a written frame left (empty when none has been written yet), for the next
  // frame's copy: a run allocates its frame buffers once, not every frame.
  FrameJob spare();
  // Queues a frame, waiting for room. Throws the first write's failure, if one failed.
  void push(FrameJob job);
  // Waits until every queued frame is written. Throws the first write's failure, if one failed.
  void drain();
  // Frames written so far.
  long written() const;

 private:
  void work();
  void throw_if_failed();  // with mutex_ held

  const std::size_t capacity_;
  std::function<void(const FrameJob&)> write_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<FrameJob> queued_;
  std::vector<FrameJob> spares_;
  bool writing_ = false;   // a job is out of the queue, being written
  bool closing_ = false;
  std::exception_ptr failure_;
  long written_ = 0;
  std::thread thread_;     // last: started once the rest is ready
};

}  // namespace bleedsim::cli
