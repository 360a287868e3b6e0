#include "reference_cpu/worker_pool.h"

namespace bleedsim {

WorkerPool& WorkerPool::shared() {
  static WorkerPool pool;
  return pool;
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

namespace {
// Set on a thread while it runs a band: a loop inside a band (on the caller or a worker) must not
// wait for the pool its own loop is holding.
thread_local bool in_band = false;

struct InBand {
  InBand() { in_band = true; }
  ~InBand() { in_band = false; }
};
}  // namespace

bool WorkerPool::try_run(int bands, const std::function<void(int)>& band) {
  if (in_band) return false;
  std::unique_lock<std::mutex> running(running_, std::try_to_lock);
  if (!running.owns_lock()) return false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    while (int(workers_.size()) < bands - 1) workers_.emplace_back([this] { work(); });
    band_ = &band;
    bands_ = bands;
    next_band_ = 1;
    bands_done_ = 1;  // band 0, the caller's, below
    ++loop_;
  }
  wake_.notify_all();
  {
    const InBand marked;
    band(0);
  }
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [&] { return bands_done_ == bands_; });
  band_ = nullptr;
  return true;
}

void WorkerPool::work() {
  std::uint64_t seen = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || loop_ != seen; });
    if (stopping_) return;
    seen = loop_;
    // Take bands while the loop has any left; a worker that finds none goes back to sleep.
    while (next_band_ < bands_) {
      const int b = next_band_++;
      lock.unlock();
      {
        const InBand marked;
        (*band_)(b);
      }
      lock.lock();
      if (++bands_done_ == bands_) finished_.notify_one();
    }
  }
}

}  // namespace bleedsim
