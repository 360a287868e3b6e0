#include "reference_cpu/worker_pool.h"

#include <chrono>

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

// claim_'s fields: the loop's number (32 bits), its bands (16) and the next band to take (16).
std::uint64_t loop_of(std::uint64_t claim) { return claim >> 32; }
int bands_of(std::uint64_t claim) { return int((claim >> 16) & 0xffffu); }
int next_of(std::uint64_t claim) { return int(claim & 0xffffu); }
constexpr int kMostBands = 0xffff;

// How long a thread waits awake for the next loop (a worker) or for the last band (the caller)
// before it sleeps. A particle step is seven loops microseconds apart, and a thread woken from sleep
// takes tens of microseconds to run again (on a virtual machine its CPU may have been halted): with
// sixteen threads, sleeping between loops cost more than the loops' work. libgomp's threads wait
// awake likewise before they sleep.
constexpr auto kWaitAwake = std::chrono::microseconds(200);

// Whether ready() came true within kWaitAwake. The thread yields while it waits, so that the
// process's other threads (a run's output encoders) keep the core when they need it.
template <class Ready>
bool became_ready_awake(const Ready& ready) {
  const auto until = std::chrono::steady_clock::now() + kWaitAwake;
  for (int polls = 1;; ++polls) {
    if (ready()) return true;
    if (polls % 32 == 0 && std::chrono::steady_clock::now() > until) return false;
    std::this_thread::yield();
  }
}
}  // namespace

bool WorkerPool::try_run(int threads, int bands, const std::function<void(int)>& band) {
  if (in_band || bands > kMostBands) return false;
  std::unique_lock<std::mutex> running(running_, std::try_to_lock);
  if (!running.owns_lock()) return false;
  std::uint64_t loop;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    while (int(workers_.size()) < threads - 1) {
      const int index = int(workers_.size());
      workers_.emplace_back([this, index] { work(index); });
    }
    band_ = &band;
    helpers_ = threads - 1;
    bands_done_ = 0;
    loop = (loop_of(claim_) + 1) & 0xffffffffu;
    claim_.store(loop << 32 | std::uint64_t(bands) << 16, std::memory_order_release);
  }
  wake_.notify_all();
  take_bands(loop);
  const auto all_done = [&] { return bands_done_.load(std::memory_order_acquire) == bands; };
  if (!became_ready_awake(all_done)) {
    std::unique_lock<std::mutex> lock(mutex_);
    finished_.wait(lock, all_done);
  }
  return true;
}

void WorkerPool::take_bands(std::uint64_t loop) {
  std::uint64_t claim = claim_.load(std::memory_order_acquire);
  while (loop_of(claim) == loop && next_of(claim) < bands_of(claim)) {
    if (!claim_.compare_exchange_weak(claim, claim + 1, std::memory_order_acq_rel)) continue;
    {
      const InBand marked;
      (*band_)(next_of(claim));
    }
    if (bands_done_.fetch_add(1, std::memory_order_acq_rel) + 1 == bands_of(claim)) {
      // The caller may be asleep (or about to be, its test made under the mutex): wake it.
      { const std::lock_guard<std::mutex> lock(mutex_); }
      finished_.notify_one();
    }
    claim = claim_.load(std::memory_order_acquire);
  }
}

void WorkerPool::work(int index) {
  std::uint64_t seen = 0;
  for (;;) {
    const auto called = [&] { return stopping_.load() || loop_of(claim_.load(std::memory_order_acquire)) != seen; };
    if (!became_ready_awake(called)) {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, called);
    }
    if (stopping_) return;
    seen = loop_of(claim_.load(std::memory_order_acquire));
    // A loop asks for as many threads as it was given, though the pool may have more.
    if (index < helpers_) take_bands(seen);
  }
}

}  // namespace bleedsim
