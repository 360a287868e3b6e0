// The run's output (cli/output_queue.h): frames encoded on several workers, several frames at once,
// and written one at a time in the order they came; a full queue holding the simulation back, so
// that the frames held (and their buffers) never pass the bound; every queued frame written on
// closing; buffers handed back for reuse; and a failed encoding or write ending the writing: the
// frames before it kept, the failure thrown to the run at its next push or drain.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cli/output_queue.h"

namespace bleedsim::cli {
namespace {

using std::chrono::microseconds;

// A frame of `tasks` parts: the encoding fills field `task` with the frame's number plus one, which
// the writing checks.
constexpr int kTasks = 3;

FrameJob job_for(FrameJob job, long frame) {
  job.frame = frame;
  job.fields.resize(kTasks);
  for (HostBytes& field : job.fields) field.assign(16, 0);
  return job;
}

std::uint8_t mark(long frame) { return std::uint8_t(frame + 1); }

OutputWork work(std::function<void(FrameJob&, int)> encode, std::function<void(const FrameJob&)> write) {
  return {[](FrameJob&) { return kTasks; },
          [encode](FrameJob& job, int task) {
            encode(job, task);
            job.fields[std::size_t(task)].assign(16, mark(job.frame));
          },
          std::move(write)};
}

bool encoded(const FrameJob& job) {
  for (const HostBytes& field : job.fields)
    if (field != HostBytes(16, mark(job.frame))) return false;
  return true;
}

std::vector<long> zero_to(long n) {
  std::vector<long> frames(static_cast<std::size_t>(n));
  for (long k = 0; k < n; ++k) frames[std::size_t(k)] = k;
  return frames;
}

TEST(OutputQueue, WritesEveryFrameInOrderAndHoldsTheRunBackWhenFull) {
  std::vector<long> order;
  std::atomic<long> pushed{0};
  long most_held = 0;  // frames pushed and not yet written, seen as each is written
  OutputQueue queue(2, 3, work([](FrameJob&, int) {}, [&](const FrameJob& job) {
                      std::this_thread::sleep_for(std::chrono::milliseconds(2));  // a slow disk, which
                      most_held = std::max(most_held, pushed.load() - job.frame);  // gives the run time to queue
                      order.push_back(job.frame);
                    }));
  int reused = 0;
  for (long k = 0; k < 50; ++k) {
    FrameJob job = queue.spare();
    reused += job.fields.size() == kTasks;
    queue.push(job_for(std::move(job), k));
    ++pushed;
  }
  queue.drain();
  EXPECT_EQ(queue.written(), 50);
  EXPECT_EQ(order, zero_to(50));
  // Never more than the three frames the queue may hold: the run waited for room.
  EXPECT_LE(most_held, 3);
  EXPECT_GE(most_held, 2);
  // Once the queue is full each push waits for a frame to be written, whose buffers come back: all
  // but the first few frames reuse them.
  EXPECT_GE(reused, 40);
}

TEST(OutputQueue, SeveralFramesEncodeAtOnceOutOfOrderAndAreWrittenInOrder) {
  // Later frames encode faster than earlier ones, so they finish first; the writer waits its turn.
  std::mutex mutex;
  std::set<long> encoding;      // frames with a task running
  std::size_t most_frames = 0;  // encoding at once
  std::vector<long> order;
  bool all_encoded = true;
  {
    OutputQueue queue(4, 6, work(
                                [&](FrameJob& job, int) {
                                  {
                                    std::lock_guard<std::mutex> lock(mutex);
                                    encoding.insert(job.frame);
                                    most_frames = std::max(most_frames, encoding.size());
                                  }
                                  std::this_thread::sleep_for(microseconds(3000 - 500 * (job.frame % 6)));
                                  std::lock_guard<std::mutex> lock(mutex);
                                  encoding.erase(job.frame);
                                },
                                [&](const FrameJob& job) {
                                  all_encoded = all_encoded && encoded(job);
                                  order.push_back(job.frame);
                                }));
    for (long k = 0; k < 60; ++k) queue.push(job_for(queue.spare(), k));
    queue.drain();
    EXPECT_EQ(queue.written(), 60);
  }
  EXPECT_EQ(order, zero_to(60));
  EXPECT_TRUE(all_encoded) << "a frame was written before all its tasks had run";
  EXPECT_GE(most_frames, 2u) << "the workers never had two frames in hand";
}

TEST(OutputQueue, TheFramesHeldAndTheirBuffersStayWithinTheBound) {
  // A slow writer and fast workers: every frame the run can queue is encoded and waits.
  constexpr std::size_t kInFlight = 5;
  std::atomic<long> pushed{0};
  long most_held = 0;
  std::set<const std::uint8_t*> buffers;  // every job the run filled, by its first field's buffer
  OutputQueue queue(3, kInFlight, work([](FrameJob&, int) {}, [&](const FrameJob& job) {
                      std::this_thread::sleep_for(std::chrono::milliseconds(1));
                      most_held = std::max(most_held, pushed.load() - job.frame);
                    }));
  for (long k = 0; k < 80; ++k) {
    FrameJob job = job_for(queue.spare(), k);
    buffers.insert(job.fields[0].data());
    queue.push(std::move(job));
    ++pushed;
  }
  queue.drain();
  EXPECT_EQ(queue.written(), 80);
  EXPECT_LE(most_held, long(kInFlight));
  EXPECT_EQ(most_held, long(kInFlight)) << "the run never filled the queue: the test did not test the bound";
  // The frames held and the one the run is filling: no more jobs than that were ever allocated.
  EXPECT_LE(buffers.size(), kInFlight + 1);
}

// What a run of 100 frames into `queue` is stopped by: the message its push or drain throws.
std::string failure_of_a_run(OutputQueue& queue) {
  try {
    for (long k = 0; k < 100; ++k) queue.push(job_for({}, k));
    queue.drain();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(OutputQueue, AFailedWriteKeepsTheFramesBeforeItAndReachesTheRun) {
  std::vector<long> order;
  OutputQueue queue(2, 3, work([](FrameJob&, int) {}, [&](const FrameJob& job) {
                      if (job.frame == 5) throw std::runtime_error("frames.h5: No space left on device");
                      order.push_back(job.frame);
                    }));
  EXPECT_EQ(failure_of_a_run(queue), "frames.h5: No space left on device");
  EXPECT_EQ(queue.written(), 5);
  EXPECT_EQ(order, zero_to(5));
  EXPECT_THROW(queue.drain(), std::runtime_error);
}

TEST(OutputQueue, AFailedEncodingKeepsTheFramesBeforeItAndReachesTheRun) {
  // Frame 5's second task fails at once, while frames 0-4 are still encoding (slowly): they are
  // written all the same, and no frame from 5 on.
  std::vector<long> order;
  OutputQueue queue(4, 8, work(
                              [](FrameJob& job, int task) {
                                if (job.frame == 5 && task == 1) throw std::runtime_error("frame_000005.png: encoder failed");
                                if (job.frame < 5) std::this_thread::sleep_for(std::chrono::milliseconds(5));
                              },
                              [&](const FrameJob& job) { order.push_back(job.frame); }));
  EXPECT_EQ(failure_of_a_run(queue), "frame_000005.png: encoder failed");
  EXPECT_EQ(queue.written(), 5);
  EXPECT_EQ(order, zero_to(5));
}

TEST(OutputQueue, ClosingEncodesAndWritesWhatIsQueued) {
  std::vector<long> order;
  bool all_encoded = true;
  {
    OutputQueue queue(3, 8, work([](FrameJob&, int) { std::this_thread::sleep_for(microseconds(500)); },
                                 [&](const FrameJob& job) {
                                   all_encoded = all_encoded && encoded(job);
                                   order.push_back(job.frame);
                                 }));
    for (long k = 0; k < 8; ++k) queue.push(job_for({}, k));
  }
  EXPECT_EQ(order, zero_to(8));
  EXPECT_TRUE(all_encoded);
}

TEST(OutputQueue, AFrameWithNothingToEncodeIsWritten) {
  std::vector<long> order;
  {
    OutputQueue queue(2, 2, {[](FrameJob&) { return 0; }, [](FrameJob&, int) { throw std::logic_error("no task"); },
                             [&](const FrameJob& job) { order.push_back(job.frame); }});
    for (long k = 0; k < 5; ++k) queue.push(job_for({}, k));
    queue.drain();
  }
  EXPECT_EQ(order, zero_to(5));
}

}  // namespace
}  // namespace bleedsim::cli
