#pragma once
// The CPU reference's worker threads, started once and kept (parallel_rows.h runs its bands on them):
// a frame calls a dozen parallel loops, and starting threads for each cost more than some loops.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace bleedsim {

class WorkerPool {
 public:
  // The process's pool; its workers are started as loops first ask for them and joined at exit.
  static WorkerPool& shared();
  ~WorkerPool();

  // Runs band(b) for every b in [0, bands), on the calling thread and threads − 1 workers, and
  // returns once all have. False, running nothing, when the pool is running another thread's loop
  // (several simulations on threads of their own): the caller then starts threads itself.
  bool try_run(int threads, int bands, const std::function<void(int)>& band);

 private:
  void work(int index);
  // Runs bands of loop `loop` one at a time until none is left to take.
  void take_bands(std::uint64_t loop);

  std::mutex running_;  // held by the thread whose loop the pool runs
  std::mutex mutex_;    // for sleeping and waking only: the bands are taken without it
  std::condition_variable wake_, finished_;
  std::vector<std::thread> workers_;
  const std::function<void(int)>* band_ = nullptr;  // the current loop's; set before it is published
  std::atomic<int> helpers_{0};  // the current loop's: the workers of index below it take part
  // The current loop's number, its band count and its next band to take, in one word: a thread
  // takes a band by advancing it, and so can never take a band of a loop it did not see.
  alignas(64) std::atomic<std::uint64_t> claim_{0};
  alignas(64) std::atomic<int> bands_done_{0};
  std::atomic<bool> stopping_{false};
};

}  // namespace bleedsim
