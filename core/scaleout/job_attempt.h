#pragma once
// One job run on this rank, timed, with what it threw kept as text (a failure crosses to rank 0 as a
// message: exceptions do not travel between processes). For run_jobs.cpp and mpi_exchange.cpp.
#include <chrono>
#include <exception>
#include <string>

#include "core/scaleout/run_jobs.h"

namespace bleedsim {

struct JobAttempt {
  JobResult result;   // the record (empty when failed) and where it ran
  bool failed = false;
  std::string error;  // what the job threw
};

inline JobAttempt attempt_job(const Ranks& ranks, std::size_t job, const JobFunction& run) {
  JobAttempt attempt;
  attempt.result.job = job;
  attempt.result.origin = JobOrigin{ranks.rank(), ranks.host(), ranks.cuda_device(), 0.0};
  const auto start = std::chrono::steady_clock::now();
  try {
    attempt.result.record = run(job);
  } catch (const std::exception& e) {
    attempt.failed = true;
    attempt.error = e.what();
  } catch (...) {
    attempt.failed = true;
    attempt.error = "an exception that is not a std::exception";
  }
  attempt.result.origin.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return attempt;
}

}  // namespace bleedsim
