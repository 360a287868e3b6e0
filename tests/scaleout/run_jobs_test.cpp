// run_jobs in one process (core/scaleout/run_jobs.cpp): every job, in order, with where it ran; a
// job that throws ends the run with its index and message. The same over MPI ranks is
// scaleout.mpi_ranks (tests/scaleout/mpi_check.py), which needs mpirun.
#include <gtest/gtest.h>

#include <unistd.h>

#include <climits>
#include <stdexcept>
#include <vector>

#include "core/runtime/backend.h"
#include "core/scaleout/run_jobs.h"
#include "tests/scaleout/toy_jobs.h"

namespace bleedsim {
namespace {

std::string this_host() {
  char name[HOST_NAME_MAX + 1] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

TEST(Ranks, WithoutALauncherThisProcessIsRankZeroOfOne) {
  const Ranks ranks;
  EXPECT_EQ(ranks.rank(), 0);
  EXPECT_EQ(ranks.size(), 1);
  EXPECT_TRUE(ranks.is_root());
  EXPECT_EQ(ranks.local_rank(), 0);
  EXPECT_EQ(ranks.host(), this_host());
  EXPECT_EQ(ranks.cuda_device(), cuda_device_count() > 0 ? 0 : -1);
  EXPECT_TRUE(ranks.all_ok(true));
  EXPECT_FALSE(ranks.all_ok(false));
}

TEST(RunJobs, AloneRunsEveryJobInOrderAndSaysWhere) {
  const Ranks ranks;
  std::vector<std::size_t> ran;
  const std::vector<JobResult> results = run_jobs(ranks, test::toy_costs(12), [&](std::size_t job) {
    ran.push_back(job);
    return test::toy_record(job);
  });
  EXPECT_EQ(ran, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
  ASSERT_EQ(results.size(), 12u);
  for (std::size_t job = 0; job < 12; ++job) {
    EXPECT_EQ(results[job].job, job);
    EXPECT_TRUE(results[job].record == test::toy_record(job)) << "job " << job;
    EXPECT_EQ(results[job].origin.rank, 0);
    EXPECT_EQ(results[job].origin.host, this_host());
    EXPECT_EQ(results[job].origin.cuda_device, ranks.cuda_device());
    EXPECT_GE(results[job].origin.seconds, 0.0);
  }
}

TEST(RunJobs, AloneRunsOnlyTheJobsGiven) {
  const Ranks ranks;
  const std::vector<JobResult> results =
      run_jobs(ranks, test::toy_costs(12), {1, 4, 11}, [](std::size_t job) { return test::toy_record(job); });
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[2].job, 11u);
  EXPECT_TRUE(results[2].record == test::toy_record(11));
  const auto none = [](std::size_t) { return std::vector<std::uint8_t>(); };
  EXPECT_THROW(run_jobs(ranks, test::toy_costs(12), {4, 1}, none), std::invalid_argument);
  EXPECT_THROW(run_jobs(ranks, test::toy_costs(12), {1, 1}, none), std::invalid_argument);
  EXPECT_THROW(run_jobs(ranks, test::toy_costs(12), {12}, none), std::invalid_argument);
  EXPECT_THROW(run_jobs(ranks, test::toy_costs(12), none, RunJobsOptions{0}), std::invalid_argument);
  EXPECT_THROW(run_jobs(ranks, test::toy_costs(12), none, RunJobsOptions{std::size_t(INT_MAX) + 1}), std::invalid_argument);
}

TEST(RunJobs, AJobThatThrowsEndsTheRunWithItsIndexAndMessage) {
  const Ranks ranks;
  std::vector<std::size_t> ran;
  try {
    run_jobs(ranks, test::toy_costs(8), [&](std::size_t job) {
      ran.push_back(job);
      if (job == 3) throw std::runtime_error("toy job 3 refused on purpose");
      return test::toy_record(job);
    });
    ADD_FAILURE() << "no JobFailed";
  } catch (const JobFailed& e) {
    EXPECT_EQ(std::string(e.what()), "job 3: toy job 3 refused on purpose");
    EXPECT_EQ(e.job(), 3u);
    EXPECT_EQ(e.origin().rank, 0);
  }
  EXPECT_EQ(ran, (std::vector<std::size_t>{0, 1, 2, 3})) << "jobs ran after the failure";
}

}  // namespace
}  // namespace bleedsim
