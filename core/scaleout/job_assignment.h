#pragma once
// Which part runs which job. A part is an MPI rank, or a shard of a Slurm job array: both use this
// one assignment, so `mpirun -n K` and `--shard i/K` split a study the same way.
#include <cstddef>
#include <vector>

namespace bleedsim {

// Longest processing time first (Graham 1969): the jobs by falling cost (ties: lower index first),
// each to the part with the least cost so far (ties: lower part). Deterministic: the same costs
// give the same owners on every rank and every machine (the loads are summed in one fixed order).
// The longest part's cost is at most total/K + (1 - 1/K)·max cost (any greedy list schedule), and
// at most (4/3 - 1/(3K)) of the best possible split (Graham's bound for this order).
// Returns each job's part, in [0, parts). Throws std::invalid_argument for parts < 1 or a cost
// that is negative or not finite (naming the job).
std::vector<int> assign_jobs(const std::vector<double>& costs, int parts);

// The jobs `owners` gives to `part`, ascending.
std::vector<std::size_t> jobs_of_part(const std::vector<int>& owners, int part);

}  // namespace bleedsim
