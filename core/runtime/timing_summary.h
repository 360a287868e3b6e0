#pragma once
// Compute times against a real-time budget: the 1 ms haptic tick, the 33.3 ms frame at 30 Hz.
// The run summary and the benchmarks report them alike.
#include <cstddef>
#include <string>
#include <vector>

namespace bleedsim {

constexpr double kHapticBudget_s = 1.0e-3;
constexpr double kFrameBudget_s = 1.0 / 30.0;

// Nearest-rank percentiles of a set of durations, in seconds.
struct Percentiles {
  std::size_t count = 0;
  double p50 = 0, p95 = 0, p99 = 0, max = 0;
};
Percentiles percentiles_of(std::vector<double> seconds);

// "p50 0.41 µs, p95 0.52 µs, p99 0.90 µs, max 7.9 µs of 4001 ticks: p99 is 0.09 % of the 1 ms budget"
std::string describe_against_budget(const Percentiles& p, const char* items, double budget_s);

}  // namespace bleedsim
