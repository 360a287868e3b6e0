#pragma once
// A run's frames written off the simulation's thread (issue 17: output off the critical path): the
// simulation hands over a copy of each frame's fields and goes on to the next. Worker threads encode
// the frames in flight, several at once: each field's HDF5 chunk through its filters, the PNGs. One
// writer thread then writes them to the files one at a time, strictly in the order they came, so the
// files are those a run writing them itself would make, byte for byte. The threads are the queue's,
// kept for the run, not reference_cpu's WorkerPool: that runs one fork-join loop at a time, its
// caller waiting, and it is the CPU simulation's, whose loops would start threads of their own
// whenever the output held it.
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
#include "core/runtime/download.h"
#include "core/runtime/image.h"

namespace bleedsim::cli {

// One frame's outputs: its fields as the host copied them, the haptic ticks replayed for it, and
// what the workers make of them. A written frame's job comes back with all its buffers (spare()).
struct FrameJob {
  long frame = 0;
  double time_s = 0.0;
  std::vector<HostBytes> fields;  // in the backend's host memory (Simulation::host_memory)
  std::vector<HapticTick> ticks;
  std::vector<std::vector<std::uint8_t>> chunks;  // each field's HDF5 chunk, filtered
  std::vector<unsigned char> png, view_png;       // the frame's and the view's PNG, when due
  Image view;                                     // the view, when a PNG or a sheet shows it
};

// What a run does with each frame.
struct OutputWork {
  // On the run's thread, as a frame is queued: readies the job for its encoding (sizes what the
  // tasks fill) and says how many tasks it has.
  std::function<int(FrameJob&)> plan;
  // Task `task` of a frame's encoding, on a worker: any frame's, in any order, several at once, so
  // a task writes only the members of the job that are its own.
  std::function<void(FrameJob&, int task)> encode;
  // An encoded frame to the files, on the writer thread, frame after frame in order.
  std::function<void(const FrameJob&)> write;
};

class OutputQueue {
 public:
  // `workers` threads encode (at least one), one writes; at most `in_flight` frames are held at once
  // (queued, encoding, encoded, or being written; at least one): with the one the run is making,
  // that many copies of a frame and its encodings are all the memory the output takes.
  OutputQueue(int workers, std::size_t in_flight, OutputWork work);
  // Encodes and writes what is still queued, unless a task failed, and ends the threads.
  ~OutputQueue();
  OutputQueue(const OutputQueue&) = delete;
  OutputQueue& operator=(const OutputQueue&) = delete;

  // A job whose buffers a written frame left (empty when none has been written yet), for the next
  // frame's copy: a run allocates its frame buffers once, not every frame.
  FrameJob spare();
  // Queues a frame, waiting for room. Throws the first failure, if an encoding or a write failed.
  void push(FrameJob job);
  // Waits until every queued frame is written. Throws the first failure, if one failed.
  void drain();
  // Frames written so far.
  long written() const;

 private:
  // A frame in flight and its tasks: handed out in order, finished in any.
  struct Slot {
    FrameJob job;
    int tasks = 0, started = 0, finished = 0;
    std::exception_ptr failure;  // its first task to fail
  };

  void encode_frames();
  void write_frames();
  Slot* next_task();       // with mutex_ held
  void throw_if_failed();  // with mutex_ held

  const std::size_t in_flight_;
  const OutputWork work_;
  mutable std::mutex mutex_;
  std::condition_variable task_ready_;  // for the workers
  std::condition_variable progress_;    // a task or a frame done, a failure: for the writer and the run
  // Frames in the order they came; only the front is ever removed (written), so a worker's reference
  // to another slot stays valid while it works unlocked.
  std::deque<Slot> slots_;
  std::vector<FrameJob> spares_;
  bool closing_ = false;
  std::exception_ptr failure_;  // ends the encoding and the writing: the frames before it are kept
  long written_ = 0;
  std::vector<std::thread> workers_;  // last: started once the rest is ready
  std::thread writer_;
};

}  // namespace bleedsim::cli
