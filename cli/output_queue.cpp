#include "cli/output_queue.h"

#include <utility>

namespace bleedsim::cli {

OutputQueue::OutputQueue(std::size_t capacity, std::function<void(const FrameJob&)> write)
    : capacity_(capacity), write_(std::move(write)), thread_([this] { work(); }) {}

OutputQueue::~OutputQueue() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

FrameJob OutputQueue::spare() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (spares_.empty()) return {};
  FrameJob job = std::move(spares_.back());
  spares_.pop_back();
  return job;
}

void OutputQueue::push(FrameJob job) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return failure_ || queued_.size() < capacity_; });
  throw_if_failed();
  queued_.push_back(std::move(job));
  changed_.notify_all();
}

void OutputQueue::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return failure_ || (queued_.empty() && !writing_); });
  throw_if_failed();
}

long OutputQueue::written() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return written_;
}

void OutputQueue::throw_if_failed() {
  if (failure_) std::rethrow_exception(failure_);
}

void OutputQueue::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return closing_ || !queued_.empty(); });
    // After a failure nothing more is written: the frames before it are what the run keeps.
    if (queued_.empty() || failure_) return;
    FrameJob job = std::move(queued_.front());
    queued_.pop_front();
    writing_ = true;
    lock.unlock();
    std::exception_ptr failed;
    try {
      write_(job);
    } catch (...) {
      failed = std::current_exception();
    }
    lock.lock();
    writing_ = false;
    if (failed) {
      failure_ = failed;
    } else {
      ++written_;
      spares_.push_back(std::move(job));
    }
    changed_.notify_all();
  }
}

}  // namespace bleedsim::cli
