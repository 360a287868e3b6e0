// assign_jobs (core/scaleout/job_assignment.cpp): every job to exactly one part, and the longest
// part within the bounds that list scheduling and Graham's longest-first order guarantee.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/scaleout/job_assignment.h"

namespace bleedsim {
namespace {

// Whole-number costs, so that every sum below is exact in a double and the bounds are checked
// without a tolerance.
std::vector<double> random_costs(std::mt19937& random, std::size_t n, int largest) {
  std::uniform_int_distribution<int> cost(0, largest);
  std::vector<double> costs(n);
  for (double& c : costs) c = cost(random);
  return costs;
}

// The longest part's total cost.
double longest(const std::vector<double>& costs, const std::vector<int>& owners, int parts) {
  std::vector<double> load(std::size_t(parts), 0.0);
  for (std::size_t j = 0; j < costs.size(); ++j) load[std::size_t(owners[j])] += costs[j];
  return *std::max_element(load.begin(), load.end());
}

// The best split's longest part, by trying every split (parts^n of them: small n only).
double optimum(const std::vector<double>& costs, int parts) {
  std::vector<int> owners(costs.size(), 0);
  double best = std::numeric_limits<double>::infinity();
  for (;;) {
    best = std::min(best, longest(costs, owners, parts));
    std::size_t j = 0;
    while (j < owners.size() && ++owners[j] == parts) owners[j++] = 0;
    if (j == owners.size()) return best;
  }
}

TEST(AssignJobs, EveryJobGoesToExactlyOnePart) {
  std::mt19937 random(1);
  for (int parts = 1; parts <= 9; ++parts) {
    for (std::size_t n : {0, 1, 2, 5, 8, 9, 17, 50}) {
      const std::vector<double> costs = random_costs(random, n, 100);
      const std::vector<int> owners = assign_jobs(costs, parts);
      ASSERT_EQ(owners.size(), n);
      // The parts' job lists, put together, are each job once.
      std::vector<std::size_t> all;
      for (int p = 0; p < parts; ++p) {
        const std::vector<std::size_t> mine = jobs_of_part(owners, p);
        EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
        all.insert(all.end(), mine.begin(), mine.end());
      }
      std::sort(all.begin(), all.end());
      std::vector<std::size_t> expected(n);
      std::iota(expected.begin(), expected.end(), std::size_t(0));
      EXPECT_EQ(all, expected) << n << " jobs in " << parts << " parts";
    }
  }
}

TEST(AssignJobs, TheLongestPartIsWithinTheListSchedulingBound) {
  // Each job went to the least loaded part, whose load was then at most (total - c)/K; so the
  // longest part ends at most at total/K + (1 - 1/K)·c ≤ total/K + (1 - 1/K)·max. Times K, in
  // whole numbers: K·longest ≤ total + (K - 1)·max.
  std::mt19937 random(2);
  for (int trial = 0; trial < 2000; ++trial) {
    const int parts = 1 + int(random() % 16);
    const std::vector<double> costs = random_costs(random, random() % 200, trial % 2 ? 1000 : 10);
    const std::vector<int> owners = assign_jobs(costs, parts);
    const double total = std::accumulate(costs.begin(), costs.end(), 0.0);
    const double max = costs.empty() ? 0.0 : *std::max_element(costs.begin(), costs.end());
    EXPECT_LE(parts * longest(costs, owners, parts), total + (parts - 1) * max) << "trial " << trial;
  }
}

TEST(AssignJobs, TheLongestPartIsWithinGrahamsBoundOfTheBestSplit) {
  // Longest first is within (4/3 - 1/(3K)) of the optimum (Graham 1969): 3K·longest ≤ (4K - 1)·best.
  std::mt19937 random(3);
  for (int trial = 0; trial < 300; ++trial) {
    const int parts = 2 + trial % 2;
    const std::vector<double> costs = random_costs(random, 4 + random() % 6, 30);
    const double best = optimum(costs, parts);
    EXPECT_LE(3 * parts * longest(costs, assign_jobs(costs, parts), parts), (4 * parts - 1) * best)
        << "trial " << trial;
  }
}

TEST(AssignJobs, GrahamsWorstCaseReachesHisBoundExactly) {
  // 2K + 1 jobs: two each of 2K-1 down to K+1, and three of K. The best split is K parts of 3K
  // (each K+i beside 2K-i, and the three Ks together); longest first gives 4K - 1. So the bound of
  // the test above is the one this order has, not a loose one.
  for (int parts = 2; parts <= 6; ++parts) {
    std::vector<double> costs;
    for (int c = 2 * parts - 1; c > parts; --c) costs.insert(costs.end(), {double(c), double(c)});
    costs.insert(costs.end(), {double(parts), double(parts), double(parts)});
    EXPECT_EQ(longest(costs, assign_jobs(costs, parts), parts), 4 * parts - 1) << parts << " parts";
    if (parts <= 3) {
      EXPECT_EQ(optimum(costs, parts), 3 * parts);
    }
  }
}

TEST(AssignJobs, EqualCostsGoRoundThePartsInJobOrder) {
  // Ties fall to the lower job and the lower part: the same answer on every rank and machine.
  EXPECT_EQ(assign_jobs(std::vector<double>(7, 1.0), 3), (std::vector<int>{0, 1, 2, 0, 1, 2, 0}));
  EXPECT_EQ(assign_jobs({5, 1, 5, 1}, 2), (std::vector<int>{0, 0, 1, 1}));
  EXPECT_EQ(assign_jobs({3, 1}, 4), (std::vector<int>{0, 1}));  // more parts than jobs: some get none
}

TEST(AssignJobs, RefusesNoPartsAndCostsThatAreNotFiniteOrAreNegative) {
  EXPECT_THROW(assign_jobs({1, 2}, 0), std::invalid_argument);
  for (const double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      assign_jobs({1, bad, 2}, 2);
      ADD_FAILURE() << "cost " << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("job 1 "), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace bleedsim
