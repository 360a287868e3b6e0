#include "core/scaleout/job_assignment.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace bleedsim {

std::vector<int> assign_jobs(const std::vector<double>& costs, int parts) {
  if (parts < 1) throw std::invalid_argument("jobs can only be split into 1 part or more, not " + std::to_string(parts));
  for (std::size_t j = 0; j < costs.size(); ++j)
    if (!std::isfinite(costs[j]) || costs[j] < 0)
      throw std::invalid_argument("job " + std::to_string(j) + " has cost " + std::to_string(costs[j]) +
                                  ": a job's cost must be finite and 0 or more");

  // The longest first; a stable sort keeps equal costs in index order.
  std::vector<std::size_t> order(costs.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });

  // Each to the least loaded part; the scan keeps the lowest part among equals.
  std::vector<double> load(std::size_t(parts), 0.0);
  std::vector<int> owners(costs.size(), 0);
  for (const std::size_t job : order) {
    const auto least = std::min_element(load.begin(), load.end());
    owners[job] = int(least - load.begin());
    *least += costs[job];
  }
  return owners;
}

std::vector<std::size_t> jobs_of_part(const std::vector<int>& owners, int part) {
  std::vector<std::size_t> jobs;
  for (std::size_t j = 0; j < owners.size(); ++j)
    if (owners[j] == part) jobs.push_back(j);
  return jobs;
}

}  // namespace bleedsim
