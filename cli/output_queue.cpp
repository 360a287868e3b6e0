#include "cli/output_queue.h"

#include <algorithm>
#include <utility>

namespace bleedsim::cli {

OutputQueue::OutputQueue(int workers, std::size_t in_flight, OutputWork work)
    : in_flight_(std::max<std::size_t>(1, in_flight)), work_(std::move(work)) {
  try {
    for (int w = 0; w < std::max(1, workers); ++w) workers_.emplace_back([this] { encode_frames(); });
    writer_ = std::thread([this] { write_frames(); });
  } catch (...) {
    // A thread the system would not start: those started end, having nothing to do.
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closing_ = true;
    }
    task_ready_.notify_all();
    progress_.notify_all();
    for (std::thread& worker : workers_) worker.join();
    throw;
  }
}

OutputQueue::~OutputQueue() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  task_ready_.notify_all();
  progress_.notify_all();
  for (std::thread& worker : workers_) worker.join();
  writer_.join();
}

FrameJob OutputQueue::spare() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (spares_.empty()) return {};
  FrameJob job = std::move(spares_.back());
  spares_.pop_back();
  return job;
}

void OutputQueue::push(FrameJob job) {
  const int tasks = work_.plan(job);
  {
    std::unique_lock<std::mutex> lock(mutex_);
    progress_.wait(lock, [&] { return failure_ || slots_.size() < in_flight_; });
    throw_if_failed();
    slots_.push_back(Slot{std::move(job), tasks, 0, 0, nullptr});
  }
  task_ready_.notify_all();
  progress_.notify_all();  // a frame with nothing to encode is ready to write
}

void OutputQueue::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  progress_.wait(lock, [&] { return failure_ || slots_.empty(); });
  throw_if_failed();
}

long OutputQueue::written() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return written_;
}

void OutputQueue::throw_if_failed() {
  if (failure_) std::rethrow_exception(failure_);
}

// The earliest frame's next task. None from a frame whose encoding failed, or from those after it:
// they will not be written.
OutputQueue::Slot* OutputQueue::next_task() {
  for (Slot& slot : slots_) {
    if (slot.failure) return nullptr;
    if (slot.started < slot.tasks) return &slot;
  }
  return nullptr;
}

void OutputQueue::encode_frames() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    Slot* slot = nullptr;
    task_ready_.wait(lock, [&] { return failure_ || (slot = next_task()) || closing_; });
    // Closing with no task left to start: every queued frame is encoded, or being encoded by another.
    if (failure_ || !slot) return;
    const int task = slot->started++;
    lock.unlock();
    std::exception_ptr failed;
    try {
      work_.encode(slot->job, task);
    } catch (...) {
      failed = std::current_exception();
    }
    lock.lock();
    if (failed && !slot->failure) slot->failure = failed;
    ++slot->finished;
    progress_.notify_all();
  }
}

void OutputQueue::write_frames() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    progress_.wait(lock, [&] {
      if (failure_ || slots_.empty()) return failure_ || closing_;
      const Slot& front = slots_.front();
      return front.failure || front.finished == front.tasks;
    });
    if (failure_ || slots_.empty()) return;
    Slot& front = slots_.front();
    std::exception_ptr failed = front.failure;
    if (!failed) {
      lock.unlock();
      try {
        work_.write(front.job);
      } catch (...) {
        failed = std::current_exception();
      }
      lock.lock();
    }
    // After a failure nothing more is encoded or written: the frames before it are what the run keeps.
    if (failed) {
      failure_ = failed;
    } else {
      ++written_;
      spares_.push_back(std::move(front.job));
      slots_.pop_front();
    }
    progress_.notify_all();
    if (failed) task_ready_.notify_all();
  }
}

}  // namespace bleedsim::cli
