#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "reference_cpu/worker_pool.h"

namespace bleedsim {

// Bands a thread takes in a loop, on average: rows cost unevenly (the pixels under the blood, the
// particles deep in a pile), and a thread that takes the next band as it finishes one evens that
// out (on 16 cores the 1080p frame with 65,536 particles fell from 13.6 to 9.4-11.1 ms).
constexpr int kBandsPerThread = 4;

// Runs row_fn(j) for every row j in [0, rows), in contiguous bands taken in turn by `threads`
// threads: the caller's and the kept workers of WorkerPool, or, when another thread's loop holds
// the pool, threads started for this loop. Each row is written by exactly one thread and depends
// on no other row, so the bytes depend neither on the thread count nor on who takes which band.
template <class RowFn>
void parallel_rows(int rows, int threads, const RowFn& row_fn) {
  const int workers = std::max(1, std::min(threads, rows));
  const int bands = workers == 1 ? 1 : std::min(rows, workers * kBandsPerThread);
  const auto run_band = [&](int band) {
    const int first = int(std::int64_t(rows) * band / bands);
    const int last = int(std::int64_t(rows) * (band + 1) / bands);
    for (int j = first; j < last; ++j) row_fn(j);
  };
  if (bands == 1) {
    run_band(0);
    return;
  }
  if (WorkerPool::shared().try_run(workers, bands, run_band)) return;
  std::atomic<int> next_band{0};
  const auto take_bands = [&] {
    for (int band = next_band++; band < bands; band = next_band++) run_band(band);
  };
  std::vector<std::thread> helpers;
  helpers.reserve(workers - 1);
  for (int helper = 1; helper < workers; ++helper) helpers.emplace_back(take_bands);
  take_bands();
  for (std::thread& helper : helpers) helper.join();
}

// Fewer particles than this are not worth starting a thread for.
constexpr int kParticlesPerThread = 4096;

// The threads a loop over `count` particles runs on: at most `threads`, at least one.
inline int threads_for_particles(int count, int threads) {
  return std::max(1, std::min(threads, count / kParticlesPerThread));
}

}  // namespace bleedsim
