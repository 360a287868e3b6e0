#pragma once
// The CPU reference's worker threads, started once and kept (parallel_rows.h runs its bands on them):
// a frame calls a dozen parallel loops, and starting threads for each cost more than some loops.
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

  // Runs band(b) for every b in [0, bands): band 0 on the calling thread, the others on workers,
  // and returns once all have. False, running nothing, when the pool is running another thread's
  // loop (several simulations on threads of their own): the caller then starts threads itself.
  bool try_run(int bands, const std::function<void(int)>& band);

 private:
  void work();

  std::mutex running_;  // held by the thread whose loop the pool runs
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::vector<std::thread> workers_;
  const std::function<void(int)>* band_ = nullptr;
  int bands_ = 0, next_band_ = 0, bands_done_ = 0;
  std::uint64_t loop_ = 0;  // counts loops, so that a worker wakes once for each
  bool stopping_ = false;
};

}  // namespace bleedsim
