#pragma once
#include <algorithm>
#include <cstdint>
#include <thread>
#include <vector>

#include "reference_cpu/worker_pool.h"

namespace bleedsim {

// Runs row_fn(j) for every row j in [0, rows), in contiguous bands over `threads` threads (the
// caller's thread and the kept workers of WorkerPool take the bands as they come free; when another
// thread's loop holds the pool, threads are started for this loop, the caller's taking the first). Each row is written by
// exactly one thread and depends on no other row, so the bytes do not depend on the thread count.
template <class RowFn>
void parallel_rows(int rows, int threads, const RowFn& row_fn) {
  const int bands = std::max(1, std::min(threads, rows));
  const auto run_band = [&](int band) {
    const int first = int(std::int64_t(rows) * band / bands);
    const int last = int(std::int64_t(rows) * (band + 1) / bands);
    for (int j = first; j < last; ++j) row_fn(j);
  };
  if (bands == 1) {
    run_band(0);
    return;
  }
  if (WorkerPool::shared().try_run(bands, run_band)) return;
  std::vector<std::thread> helpers;
  helpers.reserve(bands - 1);
  for (int band = 1; band < bands; ++band) helpers.emplace_back(run_band, band);
  run_band(0);
  for (std::thread& helper : helpers) helper.join();
}

// Fewer particles than this are not worth starting a thread for.
constexpr int kParticlesPerThread = 4096;

// The threads a loop over `count` particles runs on: at most `threads`, at least one.
inline int threads_for_particles(int count, int threads) {
  return std::max(1, std::min(threads, count / kParticlesPerThread));
}

}  // namespace bleedsim
