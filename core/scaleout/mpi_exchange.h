#pragma once
// run_jobs over several MPI ranks (mpi_exchange.cpp; built only with MPI): each rank runs the jobs
// `owners` gives it, then rank 0 gathers every record. Only run_jobs calls it.
#if BLEEDSIM_HAVE_MPI
#include <cstddef>
#include <vector>

#include "core/scaleout/run_jobs.h"

namespace bleedsim {

std::vector<JobResult> run_jobs_over_mpi(const Ranks& ranks, const std::vector<std::size_t>& jobs,
                                         const std::vector<int>& owners, const JobFunction& run,
                                         const RunJobsOptions& options);

}  // namespace bleedsim
#endif
