#include "core/study/ladder.h"

#include <cmath>
#include <stdexcept>

#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// (h0ᵖ − h1ᵖ) / (h1ᵖ − h2ᵖ) from the logarithms, written with expm1 so that it is exact near p = 0,
// where it tends to (l0 − l1)/(l1 − l2).
double difference_ratio(double l0, double l1, double l2, double p) {
  if (p == 0) return (l0 - l1) / (l1 - l2);
  return std::exp(p * (l1 - l2)) * std::expm1(p * (l0 - l1)) / std::expm1(p * (l1 - l2));
}

bool usable_step(double h) { return std::isfinite(h) && h > 0; }

std::string number(double v) { return format_significant(v, 3); }

std::string with_interval(const Estimate& e) {
  if (std::isnan(e.lo)) return number(e.value);
  return number(e.value) + " [" + number(e.lo) + ", " + number(e.hi) + "]";
}

}  // namespace

double observed_order(double h0, double h1, double h2, double ratio) {
  if (!(usable_step(h0) && usable_step(h1) && usable_step(h2)) || !(h0 > h1 && h1 > h2) || !(ratio > 0))
    return kNaN;
  const double l0 = std::log(h0), l1 = std::log(h1), l2 = std::log(h2);
  double low = -20, high = 20;
  if (ratio <= difference_ratio(l0, l1, l2, low)) return low;
  if (ratio >= difference_ratio(l0, l1, l2, high)) return high;
  for (int i = 0; i < 200 && high - low > 1e-13; ++i) {
    const double mid = (low + high) / 2;
    (difference_ratio(l0, l1, l2, mid) < ratio ? low : high) = mid;
  }
  return (low + high) / 2;
}

double richardson_weight(double h_coarse, double h_fine, double p) {
  // h_fineᵖ / (h_coarseᵖ − h_fineᵖ) = 1 / expm1(p · ln(h_coarse / h_fine)).
  return 1.0 / std::expm1(p * std::log(h_coarse / h_fine));
}

LadderFit fit_ladder(const LadderInput& in) {
  const std::size_t levels = in.levels.size();
  if (levels < 2 || in.step.size() != levels || in.labels.size() != levels)
    throw std::invalid_argument("fit_ladder: a ladder needs two levels or more, each with a step and a label");
  const std::size_t seeds = in.levels.front()->size();
  LadderFit fit;
  for (std::size_t i = 0; i + 1 < levels; ++i) fit.differences.push_back(ensemble_distance(*in.levels[i], *in.levels[i + 1]));
  const std::size_t k = fit.differences.size();
  // Order i from differences i and i + 1, on all seeds and with each left out.
  for (std::size_t i = 0; i + 1 < k; ++i) {
    const auto order = [&](double coarse_squared, double fine_squared) {
      if (!(coarse_squared > 0 && fine_squared > 0)) return kNaN;
      return observed_order(in.step[i], in.step[i + 1], in.step[i + 2], std::sqrt(coarse_squared / fine_squared));
    };
    const Distance& coarse = fit.differences[i];
    const Distance& fine = fit.differences[i + 1];
    fit.orders.push_back(jackknife_ci(seeds, order(coarse.squared.value, fine.squared.value), [&](std::size_t s) {
      return order(coarse.squared_without[s], fine.squared_without[s]);
    }));
  }
  const auto above_noise = [&](std::size_t j) { return fit.differences[j].squared.lo > 0; };
  const auto shrinking = [&](std::size_t j) { return fit.orders[j].lo > 0; };
  const auto agree = [&](std::size_t j) {
    return fit.orders[j].lo <= fit.orders[j + 1].hi && fit.orders[j + 1].lo <= fit.orders[j].hi;
  };
  // The longest run of levels ending at the finest that passes (1)–(3): its first difference a.
  for (std::size_t a = 0; a + 1 < k; ++a) {
    bool ok = true;
    for (std::size_t j = a; j < k; ++j) ok = ok && above_noise(j);
    for (std::size_t j = a; j + 1 < k; ++j) ok = ok && shrinking(j);
    for (std::size_t j = a; j + 2 < k; ++j) ok = ok && agree(j);
    if (!ok) continue;
    fit.asymptotic_from = int(a);
    fit.order = fit.orders[k - 2].value;
    fit.statement = "asymptotic from " + in.labels[a] + ": order " + with_interval(fit.orders[k - 2]);
    if (k - 1 - a > 1) fit.statement += " (" + std::to_string(k - 1 - a) + " order estimates agree)";
    return fit;
  }
  bool unchanged = true;
  for (const Distance& d : fit.differences) unchanged = unchanged && d.rms.value == 0 && !(d.rms.hi > 0);
  if (unchanged) {
    fit.statement = "unchanged: every level gives the same (the knob does not move it)";
  } else if (k < 2) {
    fit.statement = "two levels: one difference and no order (a ladder needs three levels)";
  } else if (seeds < 3) {
    fit.statement = "fewer than three seeds: no intervals, so the asymptotic range cannot be tested";
  } else if (!above_noise(k - 1)) {
    std::size_t from = k - 1;
    while (from > 0 && !above_noise(from - 1)) --from;
    fit.statement = "not asymptotic: the differences from " + in.labels[from] +
                    " on are within the seeds' noise (converged to the noise there)";
  } else if (!above_noise(k - 2)) {
    fit.statement = "not asymptotic: the finest difference stands out of the seeds' noise and the one before "
                    "it does not (the differences do not fall steadily)";
  } else if (std::isnan(fit.orders[k - 2].value)) {
    fit.statement = "not asymptotic: no order (a level without a step size, or a difference of 0)";
  } else {
    fit.statement = "not asymptotic: the differences do not shrink (order " + with_interval(fit.orders[k - 2]) + ")";
  }
  return fit;
}

}  // namespace bleedsim
