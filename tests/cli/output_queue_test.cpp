// The run's output thread (cli/output_queue.h): frames written one at a time in the order they
// came, a full queue holding the simulation back, every queued frame written by drain(), buffers
// handed back for reuse, and a failed write ending the writing: the frames before it kept, the
// failure thrown to the run at its next push or drain.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "cli/output_queue.h"

namespace bleedsim::cli {
namespace {

FrameJob job_for(long frame) {
  FrameJob job;
  job.frame = frame;
  job.fields = {std::vector<std::uint8_t>(16, std::uint8_t(frame))};
  return job;
}

TEST(OutputQueue, WritesEveryFrameInOrderAndHoldsTheRunBackWhenFull) {
  std::vector<long> order;
  std::atomic<int> waiting{0}, most_waiting{0};
  OutputQueue queue(2, [&](const FrameJob& job) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // a slow disk
    order.push_back(job.frame);
    --waiting;
  });
  int reused = 0;
  for (long k = 0; k < 50; ++k) {
    FrameJob job = queue.spare();
    reused += job.fields.size() == 1;
    job = job_for(k);
    ++waiting;
    most_waiting = std::max(most_waiting.load(), waiting.load());
    queue.push(std::move(job));
  }
  queue.drain();
  EXPECT_EQ(queue.written(), 50);
  std::vector<long> expected(50);
  for (long k = 0; k < 50; ++k) expected[k] = k;
  EXPECT_EQ(order, expected);
  // Two queued and one being written at most, and the one the run has just made.
  EXPECT_LE(most_waiting.load(), 4);
  // Once the queue is full each push waits for a frame to be written, whose buffers come back: all
  // but the first few frames reuse them.
  EXPECT_GE(reused, 40);
}

TEST(OutputQueue, AFailedWriteKeepsTheFramesBeforeItAndReachesTheRun) {
  std::vector<long> order;
  OutputQueue queue(2, [&](const FrameJob& job) {
    if (job.frame == 5) throw std::runtime_error("frames.h5: No space left on device");
    order.push_back(job.frame);
  });
  bool thrown = false;
  try {
    for (long k = 0; k < 100; ++k) queue.push(job_for(k));
    queue.drain();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_STREQ(e.what(), "frames.h5: No space left on device");
  }
  EXPECT_TRUE(thrown);
  EXPECT_EQ(queue.written(), 5);
  EXPECT_EQ(order, (std::vector<long>{0, 1, 2, 3, 4}));
  EXPECT_THROW(queue.drain(), std::runtime_error);
}

TEST(OutputQueue, ClosingWritesWhatIsQueued) {
  std::vector<long> order;
  {
    OutputQueue queue(8, [&](const FrameJob& job) { order.push_back(job.frame); });
    for (long k = 0; k < 8; ++k) queue.push(job_for(k));
  }
  EXPECT_EQ(order.size(), 8u);
}

}  // namespace
}  // namespace bleedsim::cli
