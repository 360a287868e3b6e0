#include "core/study/ensemble_stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bleedsim {
namespace {

// The regularised incomplete beta function I_x(a, b) by its continued fraction (Lentz's method, as
// in Numerical Recipes' betacf), which converges fast for x < (a + 1)/(a + b + 2); the other side
// by the symmetry I_x(a, b) = 1 − I_{1−x}(b, a).
double incomplete_beta(double a, double b, double x) {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  if (x > (a + 1) / (a + b + 2)) return 1 - incomplete_beta(b, a, 1 - x);
  constexpr double kTiny = 1e-300;
  const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) +
                                b * std::log1p(-x)) / a;
  double c = 1, d = 1 - (a + b) * x / (a + 1);
  d = 1 / (std::abs(d) < kTiny ? kTiny : d);
  double f = d;
  for (int m = 1; m <= 1000; ++m) {
    for (const bool even : {true, false}) {
      const double numerator = even ? m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m))
                                     : -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1));
      d = 1 + numerator * d;
      d = 1 / (std::abs(d) < kTiny ? kTiny : d);
      c = 1 + numerator / c;
      if (std::abs(c) < kTiny) c = kTiny;
      f *= c * d;
      if (!even && std::abs(c * d - 1) < 1e-15) return front * f;
    }
  }
  return front * f;
}

// P(T ≤ t) for t ≥ 0: 1 − ½ · I_{ν/(ν + t²)}(ν/2, ½).
double student_t_cdf(double t, int dof) {
  return 1 - 0.5 * incomplete_beta(dof / 2.0, 0.5, dof / (dof + t * t));
}

Estimate interval(double value, double half_width) { return {value, value - half_width, value + half_width}; }

}  // namespace

double student_t_975(int dof) {
  if (dof < 1) return kNaN;
  double low = 0, high = 1000;  // t(1) is 12.7; every quantile is inside
  for (int i = 0; i < 200 && high - low > 1e-12; ++i) {
    const double mid = (low + high) / 2;
    (student_t_cdf(mid, dof) < 0.975 ? low : high) = mid;
  }
  return (low + high) / 2;
}

Estimate mean_ci(const std::vector<double>& values) {
  const std::size_t n = values.size();
  if (n == 0) return {};
  double mean = 0;
  for (const double v : values) mean += v;
  mean /= double(n);
  if (n < 2) return {mean, kNaN, kNaN};
  double squares = 0;
  for (const double v : values) squares += (v - mean) * (v - mean);
  const double error = std::sqrt(squares / double(n - 1) / double(n));
  return interval(mean, student_t_975(int(n) - 1) * error);
}

Estimate jackknife_ci(std::size_t n, double full, const std::function<double(std::size_t)>& leave_out) {
  if (n < 2 || !std::isfinite(full)) return {full, kNaN, kNaN};
  std::vector<double> partial(n);
  double mean = 0;
  for (std::size_t i = 0; i < n; ++i) {
    partial[i] = leave_out(i);
    if (!std::isfinite(partial[i])) return {full, kNaN, kNaN};
    mean += partial[i];
  }
  mean /= double(n);
  double squares = 0;
  for (const double p : partial) squares += (p - mean) * (p - mean);
  const double error = std::sqrt(double(n - 1) / double(n) * squares);
  return interval(full, student_t_975(int(n) - 1) * error);
}

namespace {

// The mean over the components of term(m, M2, seeds), m and M2 a component's mean and sum of squared
// deviations over the seeds (values(s, c)): `full` with every seed, without[i] with seed i left out,
// whose M2 is M2 − n/(n − 1) · (v_i − m)² (v_i's deviation from the others' mean is n/(n − 1) times
// its deviation from m). Without needs three seeds (a variance of the two left).
template <class Values, class Term>
void over_components(std::size_t n, std::size_t components, const Values& values, const Term& term,
                     double& full, std::vector<double>& without) {
  full = 0;
  without.assign(n, 0.0);
  std::vector<double> v(n);
  for (std::size_t c = 0; c < components; ++c) {
    double mean = 0;
    for (std::size_t s = 0; s < n; ++s) mean += (v[s] = values(s, c));
    mean /= double(n);
    double m2 = 0;
    for (std::size_t s = 0; s < n; ++s) m2 += (v[s] - mean) * (v[s] - mean);
    full += term(mean, m2, n);
    if (n < 3) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const double mean_i = (mean * double(n) - v[i]) / double(n - 1);
      const double m2_i = std::max(0.0, m2 - double(n) / double(n - 1) * (v[i] - mean) * (v[i] - mean));
      without[i] += term(mean_i, m2_i, n - 1);
    }
  }
  full /= double(components);
  for (double& w : without) w = n < 3 ? kNaN : w / double(components);
}

std::size_t components_of(const SeedValues& x) {
  if (x.empty() || x.front().empty()) throw std::invalid_argument("ensemble statistics: no seeds or no components");
  for (const std::vector<double>& seed : x)
    if (seed.size() != x.front().size()) throw std::invalid_argument("ensemble statistics: seeds of unequal length");
  return x.front().size();
}

double root(double squared) { return std::sqrt(std::max(squared, 0.0)); }

}  // namespace

Distance ensemble_distance(const SeedValues& x, const SeedValues& y) {
  const std::size_t n = x.size(), components = components_of(x);
  if (y.size() != n || components_of(y) != components)
    throw std::invalid_argument("ensemble_distance: the two settings' seeds or components differ");
  double full = 0;
  std::vector<double> without;
  // d̄² − s_d²/n with s_d² = M2/(n − 1).
  over_components(
      n, components, [&](std::size_t s, std::size_t c) { return x[s][c] - y[s][c]; },
      [](double mean, double m2, std::size_t seeds) {
        return mean * mean - m2 / double(seeds - 1) / double(seeds);
      },
      full, without);
  Distance d;
  d.squared = jackknife_ci(n, full, [&](std::size_t i) { return without[i]; });
  d.rms = {root(d.squared.value), root(d.squared.lo), root(d.squared.hi)};
  d.squared_without = without;
  return d;
}

Estimate seed_spread(const SeedValues& x) {
  const std::size_t n = x.size(), components = components_of(x);
  if (n < 2) return {};
  double full = 0;
  std::vector<double> without;
  over_components(
      n, components, [&](std::size_t s, std::size_t c) { return x[s][c]; },
      [](double, double m2, std::size_t seeds) { return 2 * m2 / double(seeds - 1); }, full, without);
  return jackknife_ci(n, std::sqrt(full), [&](std::size_t i) { return std::sqrt(without[i]); });
}

Estimate pair_mean(std::size_t n, const std::function<double(std::size_t, std::size_t)>& f) {
  if (n < 2) return {};
  std::vector<double> value(n * n, 0.0);
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) sum += (value[i * n + j] = f(i, j));
  const double pairs = double(n * (n - 1) / 2);
  const double full = sum / pairs;
  return jackknife_ci(n, full, [&](std::size_t out) {
    if (n < 3) return kNaN;
    double rest = sum;
    for (std::size_t k = 0; k < n; ++k)
      if (k != out) rest -= value[std::min(k, out) * n + std::max(k, out)];
    return rest / double((n - 1) * (n - 2) / 2);
  });
}

}  // namespace bleedsim
