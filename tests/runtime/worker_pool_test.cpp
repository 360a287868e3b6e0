// The CPU reference's kept workers (reference_cpu/worker_pool.h) under parallel_rows: every row run
// exactly once, whatever the thread count, from several threads at once (the pool runs one loop,
// the others start their own threads), a loop inside a band, and loops that find the workers awake
// or asleep.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "reference_cpu/parallel_rows.h"

namespace bleedsim {
namespace {

std::vector<int> run_counts(int rows, int threads) {
  std::vector<std::atomic<int>> seen(rows);
  parallel_rows(rows, threads, [&](int j) { ++seen[j]; });
  std::vector<int> counts;
  for (const auto& s : seen) counts.push_back(s.load());
  return counts;
}

TEST(WorkerPool, EveryRowRunsOnceForAnyThreadCount) {
  for (const int threads : {1, 2, 3, 7, 16, 64})
    for (const int rows : {1, 5, 64, 1000}) EXPECT_EQ(run_counts(rows, threads), std::vector<int>(rows, 1));
}

TEST(WorkerPool, LoopsFromSeveralThreadsAtOnceEachRunEveryRow) {
  std::vector<std::thread> callers;
  std::atomic<int> wrong{0};
  for (int c = 0; c < 4; ++c)
    callers.emplace_back([&] {
      for (int repeat = 0; repeat < 200; ++repeat)
        if (run_counts(257, 5) != std::vector<int>(257, 1)) ++wrong;
    });
  for (std::thread& caller : callers) caller.join();
  EXPECT_EQ(wrong.load(), 0);
}

// Loops back to back find the workers still waiting awake for the next; after a pause of a
// millisecond (five times the time they wait awake) they have gone to sleep and must be woken.
TEST(WorkerPool, LoopsFindTheWorkersAwakeOrAsleepAndRunEveryRow) {
  for (int repeat = 0; repeat < 60; ++repeat) {
    const auto pause = std::chrono::microseconds(repeat % 3 == 0 ? 0 : repeat % 3 == 1 ? 20 : 1000);
    std::this_thread::sleep_for(pause);
    ASSERT_EQ(run_counts(97, 1 + repeat % 9), std::vector<int>(97, 1)) << "loop " << repeat;
  }
}

TEST(WorkerPool, ALoopInsideABandRunsEveryRow) {
  std::vector<std::atomic<int>> seen(40 * 30);
  parallel_rows(40, 4, [&](int j) { parallel_rows(30, 3, [&](int i) { ++seen[j * 30 + i]; }); });
  for (const auto& s : seen) ASSERT_EQ(s.load(), 1);
}

}  // namespace
}  // namespace bleedsim
