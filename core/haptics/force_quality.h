#pragma once
// The quality of the force a contact renders (docs/haptics.md, "Force quality"): small pure
// functions over one contact's ticks, each the formula the docs state, so that each can be checked
// against a closed form on a synthetic signal (tests/haptics/force_quality_test.cpp).
//
// A contact's ticks are n = 0 … L−1, its first tick in contact to its last, T apart. The force
// before the first is zero (out of contact the loop sends none); so is the force after the last,
// when the contact was released within the run.
#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace bleedsim {

// The frequency above which a force is oscillation rather than the hand's doing: a hand's voluntary
// motion stays below about 10 Hz (Brooks 1990, "Telerobotic response requirements") and its
// physiological tremor at 8–12 Hz (docs/traces.md, "The tremor"); 30 Hz is three times both.
constexpr double kHandCutoff_hz = 30.0;

// A metric's value, or why this contact cannot give one.
struct Metric {
  double value = std::numeric_limits<double>::quiet_NaN();
  std::string unavailable;  // empty when the value is there

  static Metric of(double value) { return {value, {}}; }
  static Metric none(std::string why) { return {std::numeric_limits<double>::quiet_NaN(), std::move(why)}; }
  bool available() const { return unavailable.empty(); }
};

// The 10–90 % rise time, s: from the force's first crossing of 10 % of the contact's peak to its first
// crossing of 90 %, each found by linear interpolation between the ticks either side (the one before
// the first tick at zero force). Not available without force, or when the peak is on the first tick
// (the rise then lies inside one tick, below what the loop resolves: so for a contact of one tick).
Metric rise_time_s(const std::vector<double>& force_N, double period_s);

// The force's rate of change |F_n − F_{n−1}| / T (N/s) — the "jerk" of the force — over the
// contact's steps: into the first tick from zero, between its ticks, and, when `released`, from its
// last tick back to zero. Nearest-rank percentiles, as the run's timings (core/runtime/timing_summary.h).
struct ForceRate {
  double p50_N_per_s = 0, p99_N_per_s = 0, max_N_per_s = 0;
};
ForceRate force_rate(const std::vector<Eigen::Vector3d>& force_N, bool released, double period_s);

// The force's oscillation: its power above `cutoff_hz` in the contact's discrete Fourier transform,
// P_above = Σ |X_k|² / L² over the bins k whose frequency min(k, L − k) / (L·T) is above the cutoff.
// Reported as its root, N (the RMS of the force above the cutoff), and as a share of the force's
// power about its mean (Σ over every bin but k = 0). Not available on fewer ticks than one period of
// the cutoff (L·T < 1/cutoff): every bin but the mean would then lie above it. A constant force has
// none (0, exactly), and no share.
struct Oscillation {
  Metric rms_above_N;
  Metric share_above;
};
Oscillation oscillation(const std::vector<double>& force_N, double cutoff_hz, double period_s);
// The fewest ticks whose spectrum has a bin at or below the cutoff besides the mean: ⌈1 / (cutoff·T)⌉.
std::size_t oscillation_min_ticks(double cutoff_hz, double period_s);

// The overshoot, N: the most the force exceeds what the tissue's spring alone pushes at the tick's
// depth, F_n − k·p_n — the damper's push on impact, or any ringing above the spring — and 0 when it
// never does. (Where the clamp holds the force at f_max, k·p_n is above it: no overshoot.)
double overshoot_N(const std::vector<double>& force_N, const std::vector<double>& penetration_m, double stiffness_N_per_m);

// The passivity margin over the contact: Hannaford & Ryu's passivity observer (IEEE Trans. Robotics
// and Automation 18(1), 2002), E(n) = Σ_{j≤n} f_j · v_j · T, taken as the energy the hand has put into
// the rendered tissue, with the device's own damping B added as Colgate & Schenkel's condition
// counts it. Each force F_j is held through its tick, while the tip moves Δx_j = x_{j+1} − x_j:
//
//   D_j = B · |Δx_j|² / T       what the device's damping dissipates in that tick
//   W_j = F_j · Δx_j            the work the held force does on the device (returned to the hand)
//   M(n) = Σ_{j=0}^{n} (D_j − W_j)
//
// M ≥ 0 at every tick is passivity with the device's damping; a negative M is energy the rendering
// has injected. `position_m` holds x_0 … x_L — the tip at every tick of the contact and at the first
// tick after it — or x_0 … x_{L−1} when the run ended in contact (the last hold is then unknown).
struct EnergyMargin {
  std::vector<double> after_tick_J;  // M(n) for each completed hold n
  double end_J = 0;                  // M at the contact's last completed hold
  Metric worst_J;                    // the least M(n): not available before a hold completes
  std::size_t worst_tick = 0;        // its n
};
EnergyMargin energy_margin(const std::vector<Eigen::Vector3d>& position_m, const std::vector<Eigen::Vector3d>& force_N,
                           double device_damping_Ns_per_m, double period_s);

// The ticks at the force cap f_max, where the loop's clamp holds the force down. On the tissue mesh
// the force is f_max times a unit normal, whose length is f_max to a few units in the last place;
// 8 of them are allowed.
std::int64_t ticks_at_force_limit(const std::vector<double>& force_N, double max_force_N);

}  // namespace bleedsim
