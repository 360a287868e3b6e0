#pragma once
// Runs independent jobs spread over the ranks and gathers their records on rank 0, in job order.
// Content-agnostic: a job is an index, its result an opaque record (a study's JobRecord). Which
// rank runs which job is assign_jobs over the jobs' costs (core/scaleout/job_assignment.h); each
// rank runs its own in ascending order. With one rank (no MPI in this build, no launcher, or
// `mpirun -n 1`) every job runs here, in order, and nothing else is involved.
//
//   Ranks ranks;                                   // for the whole command
//   auto results = run_jobs(ranks, costs, [&](std::size_t j) { return study.run_job(j, ...); });
//   if (ranks.is_root()) analyse(results);         // every job's record, in job order
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/scaleout/job_result.h"
#include "core/scaleout/ranks.h"

namespace bleedsim {

using JobFunction = std::function<std::vector<std::uint8_t>(std::size_t job)>;

struct RunJobsOptions {
  // The largest single MPI message. A longer record goes in pieces of this size: an MPI count is
  // an int, so one message cannot carry 2 GiB or more. Set smaller only to test the pieces.
  std::size_t max_message_bytes = std::size_t(1) << 30;
};

// A job threw. Thrown on every rank, after every rank has stopped: a failing rank tells the others
// at once, each stops before its next job, and rank 0 names the failure with the lowest job index.
// what(): "job 7 on rank 1 of 2 (host node3, CUDA device 1): <the job's message>" ("job 7:
// <message>" in one process), and how many other jobs failed, if any. Print it on rank 0 only,
// then let Ranks end MPI on every rank before exiting non-zero.
class JobFailed : public std::runtime_error {
 public:
  JobFailed(std::size_t job, const JobOrigin& origin, int ranks, const std::string& message, int other_failures);
  std::size_t job() const { return job_; }
  const JobOrigin& origin() const { return origin_; }

 private:
  std::size_t job_;
  JobOrigin origin_;
};

// Runs jobs 0 to costs.size() - 1 (costs: each job's relative time, for balance; finite, ≥ 0).
// Rank 0 returns every job's result, in job order; the other ranks return nothing. Call it on
// every rank with the same costs.
std::vector<JobResult> run_jobs(const Ranks& ranks, const std::vector<double>& costs, const JobFunction& run,
                                const RunJobsOptions& options = {});
// Runs only `jobs` (ascending indices into costs: a shard's), spread over the ranks by their costs.
// Rank 0 returns their results in the order of `jobs`. Throws std::invalid_argument for an index
// out of range or out of order.
std::vector<JobResult> run_jobs(const Ranks& ranks, const std::vector<double>& costs,
                                const std::vector<std::size_t>& jobs, const JobFunction& run,
                                const RunJobsOptions& options = {});

}  // namespace bleedsim
