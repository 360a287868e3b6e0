#include "core/runtime/timing_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// Microseconds below a millisecond, milliseconds above: three significant digits either way.
std::string duration_text(double s) {
  return s < 1e-3 ? format_significant(s * 1e6, 3) + " µs" : format_significant(s * 1e3, 3) + " ms";
}

}  // namespace

Percentiles percentiles_of(std::vector<double> seconds) {
  Percentiles p;
  p.count = seconds.size();
  if (seconds.empty()) return p;
  std::sort(seconds.begin(), seconds.end());
  const auto rank = [&](double q) {
    const std::size_t r = std::size_t(std::ceil(q * double(seconds.size())));
    return seconds[std::clamp<std::size_t>(r, 1, seconds.size()) - 1];
  };
  p.p50 = rank(0.50);
  p.p95 = rank(0.95);
  p.p99 = rank(0.99);
  p.max = seconds.back();
  return p;
}

std::string describe_against_budget(const Percentiles& p, const char* items, double budget_s) {
  char tail[160];
  std::snprintf(tail, sizeof tail, " of %zu %s: p99 is %.3g %% of the %s budget%s", p.count, items,
                100.0 * p.p99 / budget_s, duration_text(budget_s).c_str(),
                p.max > budget_s ? " (the slowest went over)" : "");
  return "p50 " + duration_text(p.p50) + ", p95 " + duration_text(p.p95) + ", p99 " + duration_text(p.p99) +
         ", max " + duration_text(p.max) + tail;
}

}  // namespace bleedsim
