#include "core/haptics/force_quality.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/haptics/power_spectrum.h"
#include "core/runtime/message_text.h"
#include "core/runtime/timing_summary.h"

namespace bleedsim {
namespace {

// Where the force first reaches `level`, in ticks from the first (the tick before it at zero force),
// interpolated linearly between the ticks either side. The level must be reached.
double first_crossing_tick(const std::vector<double>& force_N, double level) {
  double before = 0.0;
  for (std::size_t n = 0; n < force_N.size(); ++n) {
    if (force_N[n] >= level) return double(n) - 1.0 + (level - before) / (force_N[n] - before);
    before = force_N[n];
  }
  return double(force_N.size());  // unreached: the callers' levels are at most the peak
}

}  // namespace

Metric rise_time_s(const std::vector<double>& force_N, double period_s) {
  if (force_N.empty()) return Metric::none("no ticks");
  const auto peak = std::max_element(force_N.begin(), force_N.end());
  if (*peak <= 0) return Metric::none("no force in this contact");
  if (peak == force_N.begin())
    return Metric::none(force_N.size() == 1 ? "a contact of 1 tick: the force has no rise to measure"
                                            : "the force peaks on the contact's first tick: it rises within one tick");
  return Metric::of((first_crossing_tick(force_N, 0.9 * *peak) - first_crossing_tick(force_N, 0.1 * *peak)) * period_s);
}

ForceRate force_rate(const std::vector<Eigen::Vector3d>& force_N, bool released, double period_s) {
  std::vector<double> rates;
  rates.reserve(force_N.size() + 1);
  Eigen::Vector3d before = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& f : force_N) {
    rates.push_back((f - before).norm() / period_s);
    before = f;
  }
  if (released && !force_N.empty()) rates.push_back(before.norm() / period_s);
  const Percentiles p = percentiles_of(std::move(rates));
  return {p.p50, p.p99, p.max};
}

std::size_t oscillation_min_ticks(double cutoff_hz, double period_s) {
  // 1/(cutoff·T) may be a whole number that rounding lifts by an ulp (40.000000000000007 at 25 Hz):
  // a relative 1e-9 is far above that rounding and far below a tick.
  const double ticks = 1.0 / (cutoff_hz * period_s);
  return std::size_t(std::ceil(ticks * (1 - 1e-9)));
}

Oscillation oscillation(const std::vector<double>& force_N, double cutoff_hz, double period_s) {
  const std::size_t n = force_N.size();
  const std::size_t needed = oscillation_min_ticks(cutoff_hz, period_s);
  if (n < needed) {
    const std::string why = "a contact of " + std::to_string(n) + " tick" + (n == 1 ? "" : "s") +
                            " is shorter than one period of the " + format_number(cutoff_hz) + " Hz cutoff (" +
                            std::to_string(needed) + " ticks): every frequency it resolves but its mean lies above";
    return {Metric::none(why), Metric::none(why)};
  }
  Oscillation o;
  // A constant force's transform is its mean alone; the computed one would add rounding elsewhere.
  if (std::adjacent_find(force_N.begin(), force_N.end(), std::not_equal_to<>()) == force_N.end()) {
    o.rms_above_N = Metric::of(0.0);
    o.share_above = Metric::none("the force is constant: it has no oscillation to share");
    return o;
  }
  const std::vector<double> power = power_spectrum(force_N);
  const double cutoff_bin = cutoff_hz * double(n) * period_s;  // bin k is k / (L·T) Hz
  double above = 0, varying = 0;
  for (std::size_t k = 1; k < n; ++k) {
    varying += power[k];
    if (double(std::min(k, n - k)) > cutoff_bin) above += power[k];
  }
  o.rms_above_N = Metric::of(std::sqrt(above));
  o.share_above = Metric::of(above / varying);
  return o;
}

double overshoot_N(const std::vector<double>& force_N, const std::vector<double>& penetration_m, double stiffness_N_per_m) {
  double most = 0;
  for (std::size_t n = 0; n < force_N.size(); ++n) most = std::max(most, force_N[n] - stiffness_N_per_m * penetration_m[n]);
  return most;
}

EnergyMargin energy_margin(const std::vector<Eigen::Vector3d>& position_m, const std::vector<Eigen::Vector3d>& force_N,
                           double device_damping_Ns_per_m, double period_s) {
  EnergyMargin margin;
  const std::size_t holds = std::min(force_N.size(), position_m.empty() ? 0 : position_m.size() - 1);
  if (holds == 0) margin.worst_J = Metric::none("no tick's hold has completed: the run ended on the contact's first tick");
  double sum = 0;
  for (std::size_t j = 0; j < holds; ++j) {
    const Eigen::Vector3d step = position_m[j + 1] - position_m[j];
    sum += device_damping_Ns_per_m * step.squaredNorm() / period_s - force_N[j].dot(step);
    margin.after_tick_J.push_back(sum);
    if (j == 0 || sum < margin.worst_J.value) {
      margin.worst_J = Metric::of(sum);
      margin.worst_tick = j;
    }
  }
  margin.end_J = sum;
  return margin;
}

std::int64_t ticks_at_force_limit(const std::vector<double>& force_N, double max_force_N) {
  const double at_cap = max_force_N * (1 - 8 * std::numeric_limits<double>::epsilon());
  return std::count_if(force_N.begin(), force_N.end(), [at_cap](double f) { return f >= at_cap; });
}

}  // namespace bleedsim
