#include "core/scaleout/run_jobs.h"

#include <climits>
#include <numeric>

#include "core/scaleout/job_assignment.h"
#include "core/scaleout/job_attempt.h"
#include "core/scaleout/mpi_exchange.h"

namespace bleedsim {
namespace {

std::string failure_text(std::size_t job, const JobOrigin& origin, int ranks, const std::string& message,
                         int other_failures) {
  std::string text = "job " + std::to_string(job);
  if (ranks > 1) {
    text += " on rank " + std::to_string(origin.rank) + " of " + std::to_string(ranks) + " (host " + origin.host;
    if (origin.cuda_device >= 0) text += ", CUDA device " + std::to_string(origin.cuda_device);
    text += ")";
  }
  text += ": " + message;
  if (other_failures > 0)
    text += " (and " + std::to_string(other_failures) + " other job" + (other_failures == 1 ? "" : "s") + " failed)";
  return text;
}

}  // namespace

JobFailed::JobFailed(std::size_t job, const JobOrigin& origin, int ranks, const std::string& message,
                     int other_failures)
    : std::runtime_error(failure_text(job, origin, ranks, message, other_failures)), job_(job), origin_(origin) {}

std::vector<JobResult> run_jobs(const Ranks& ranks, const std::vector<double>& costs, const JobFunction& run,
                                const RunJobsOptions& options) {
  std::vector<std::size_t> every(costs.size());
  std::iota(every.begin(), every.end(), std::size_t(0));
  return run_jobs(ranks, costs, every, run, options);
}

std::vector<JobResult> run_jobs(const Ranks& ranks, const std::vector<double>& costs,
                                const std::vector<std::size_t>& jobs, const JobFunction& run,
                                const RunJobsOptions& options) {
  if (options.max_message_bytes < 1 || options.max_message_bytes > std::size_t(INT_MAX))
    throw std::invalid_argument("run_jobs: max_message_bytes must be from 1 to INT_MAX (an MPI count is an int)");
  std::vector<double> job_costs;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (jobs[i] >= costs.size() || (i > 0 && jobs[i] <= jobs[i - 1]))
      throw std::invalid_argument("run_jobs: the jobs must be ascending indices below " + std::to_string(costs.size()) +
                                  " (job " + std::to_string(jobs[i]) + " at place " + std::to_string(i) + ")");
    job_costs.push_back(costs[jobs[i]]);
  }
  // These checks, and the costs' in assign_jobs, throw on every rank alike (the same arguments)
  // before any rank runs a job or sends a message: no rank is left waiting.
  const std::vector<int> owners = assign_jobs(job_costs, ranks.size());

#if BLEEDSIM_HAVE_MPI
  if (ranks.size() > 1) return run_jobs_over_mpi(ranks, jobs, owners, run, options);
#endif
  // One process: each job in turn, the first failure ends the run.
  std::vector<JobResult> results;
  for (const std::size_t job : jobs) {
    JobAttempt attempt = attempt_job(ranks, job, run);
    if (attempt.failed) throw JobFailed(job, attempt.result.origin, 1, attempt.error, 0);
    results.push_back(std::move(attempt.result));
  }
  return results;
}

}  // namespace bleedsim
