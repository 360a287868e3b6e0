// The force-quality metrics (core/haptics/force_quality.h) on synthetic signals whose values are known
// in closed form: a step (its rate), sinusoids of known frequency (their power above and below the
// cutoff), a spring held through each tick and one a tick late on a known motion (the energy each
// injects), the clamp. Each bound is derived beside its assertion. The ramp into a spring, through
// the haptic loop itself, is in contact_quality_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "core/haptics/force_quality.h"
#include "tests/haptics/transform_error_bound.h"

namespace bleedsim {
namespace {

constexpr double kT = 0.001;  // the loop's period
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.14159265358979323846;

std::vector<Eigen::Vector3d> along_z(const std::vector<double>& f) {
  std::vector<Eigen::Vector3d> v;
  for (double x : f) v.emplace_back(0, 0, x);
  return v;
}

// --- The force's rate: a step -------------------------------------------------------------------

TEST(ForceRate, AStepIsItsHeightOverOneTickAtOnsetAndReleaseAndZeroBetween) {
  // F = 0 before, F0 for L ticks, 0 after (released): the rates are F0/T, L − 1 zeros, F0/T. Sorted,
  // the nearest ranks of L + 1 = 101 values: p50 is the 51st (a zero), p99 the 100th (F0/T).
  const double f0 = 2.5;
  const std::vector<double> step(100, f0);
  const ForceRate r = force_rate(along_z(step), true, kT);
  // |F0 − 0| / T is one division: within ε/2 of F0/T relative.
  EXPECT_EQ(r.p50_N_per_s, 0.0);
  EXPECT_NEAR(r.p99_N_per_s, f0 / kT, kEps * f0 / kT);
  EXPECT_NEAR(r.max_N_per_s, f0 / kT, kEps * f0 / kT);
  // Unreleased (the run ended in contact), there are only L rates: 1 step and 99 zeros, so the 99th
  // (p99) is a zero and only the maximum sees the step.
  const ForceRate open = force_rate(along_z(step), false, kT);
  EXPECT_EQ(open.p99_N_per_s, 0.0);
  EXPECT_NEAR(open.max_N_per_s, f0 / kT, kEps * f0 / kT);
}

TEST(ForceRate, ARateIsTheForceVectorsChange) {
  // From (3, 0, 4) N to (0, 0, 0) over a tick is 5 N in 1 ms: 5000 N/s; the direction counts.
  const ForceRate r = force_rate({Eigen::Vector3d(3, 0, 4)}, true, kT);
  EXPECT_NEAR(r.max_N_per_s, 5000.0, 2 * kEps * 5000.0);  // a norm (√ of exact squares) and a division
  EXPECT_NEAR(r.p50_N_per_s, 5000.0, 2 * kEps * 5000.0);
}

// --- Rise time on signals made tick by tick --------------------------------------------------------

TEST(RiseTime, ALinearRiseIsFourFifthsOfItsPeakOverItsSlope) {
  // F_n = s·(n + 1) for n = 0 … 99, then held: the line through the zero before tick 0. Its peak is
  // 100·s, crossed at 10 % on tick 9 and at 90 % on tick 89 exactly: a rise of 80 ticks, 0.08 s. Each
  // crossing's fraction (L − F_{n−1}) / (F_n − F_{n−1}) takes differences of about s between values up
  // to 100·s, each rounded to ε of itself: within about 2·100·ε ticks, so 8·100·ε ticks covers both
  // crossings and the product by T.
  std::vector<double> f;
  const double s = 0.013;
  for (int n = 0; n < 100; ++n) f.push_back(s * (n + 1));
  f.insert(f.end(), 50, f.back());
  const Metric rise = rise_time_s(f, kT);
  ASSERT_TRUE(rise.available()) << rise.unavailable;
  EXPECT_NEAR(rise.value, 0.080, (8 * kEps * 100) * kT);
}

TEST(RiseTime, ATooShortOrFlatContactSaysWhyItHasNone) {
  const Metric one = rise_time_s({1.0}, kT);
  EXPECT_FALSE(one.available());
  EXPECT_TRUE(std::isnan(one.value));
  EXPECT_EQ(one.unavailable, "a contact of 1 tick: the force has no rise to measure");
  EXPECT_EQ(rise_time_s({1.0, 1.0, 0.5}, kT).unavailable,
            "the force peaks on the contact's first tick: it rises within one tick");
  EXPECT_EQ(rise_time_s({0.0, 0.0}, kT).unavailable, "no force in this contact");
}

// --- Oscillation: sinusoids at known frequencies ---------------------------------------------------

// C + A·sin(2π·k0·n/N): k0 whole periods over N ticks, i.e. k0/(N·T) Hz. The angle is reduced exactly
// (k0·n mod N) before one product and one division, so each sample is within |A|·(2π + 1)·2ε + |C|·ε
// of the exact sinusoid: a deviation whose power in any set of bins is at most its own mean square.
std::vector<double> sinusoid(std::size_t n, std::size_t k0, double amplitude, double mean) {
  std::vector<double> x(n);
  for (std::size_t j = 0; j < n; ++j) x[j] = mean + amplitude * std::sin(2 * kPi * double((k0 * j) % n) / double(n));
  return x;
}
double sample_error(double amplitude, double mean) { return std::abs(amplitude) * (2 * kPi + 1) * 2 * kEps + std::abs(mean) * kEps; }

// The computed RMS of a set of bins is within ρ·RMS(x) of the exact one (||δX_S|| ≤ ||δX|| ≤ ρ·||X||,
// and ||X||/N = RMS(x) by Parseval), and the samples' own deviation adds at most its RMS (above).
double rms_bound(std::size_t n, double amplitude, double mean) {
  const double rms = std::sqrt(mean * mean + amplitude * amplitude / 2);
  return test::transform_error(n) * rms + sample_error(amplitude, mean);
}

TEST(Oscillation, ASinusoidAboveTheCutoffIsAllOscillation) {
  // 50 Hz over 1 s (N = 1000, Bluestein's path): all its power A²/2 lies in bins 50 and 950, above
  // 30 Hz; RMS above = A/√2, share 1. The mean C lies in bin 0, never above.
  const std::size_t n = 1000;
  const double a = 0.2, c = 1.0;
  const Oscillation o = oscillation(sinusoid(n, 50, a, c), kHandCutoff_hz, kT);
  ASSERT_TRUE(o.rms_above_N.available()) << o.rms_above_N.unavailable;
  EXPECT_NEAR(o.rms_above_N.value, a / std::sqrt(2.0), rms_bound(n, a, c));
  // share = above / (total − mean²): both within the bound of A²/2, so the share within 4·bound·√2/A.
  EXPECT_NEAR(o.share_above.value, 1.0, 4 * rms_bound(n, a, c) * std::sqrt(2.0) / a);
}

TEST(Oscillation, ASinusoidBelowTheCutoffHasNone) {
  // 10 Hz (a hand's tremor) over 1 s: bins 10 and 990, below 30 Hz: nothing above but rounding.
  const std::size_t n = 1000;
  const double a = 0.2, c = 1.0;
  const Oscillation o = oscillation(sinusoid(n, 10, a, c), kHandCutoff_hz, kT);
  EXPECT_LE(o.rms_above_N.value, rms_bound(n, a, c));
  EXPECT_LE(o.share_above.value, 2 * std::pow(rms_bound(n, a, c), 2) / (a * a / 2));
}

TEST(Oscillation, TheCutoffFallsBetweenTheBinsEitherSideOfIt) {
  // N = 1024 ticks (radix-2): bin k is k·1000/1024 Hz; bin 30 is 29.30 Hz (below 30), bin 31 is
  // 30.27 Hz (above).
  const std::size_t n = 1024;
  const double a = 0.3, c = 0.5;
  EXPECT_LE(oscillation(sinusoid(n, 30, a, c), kHandCutoff_hz, kT).rms_above_N.value, rms_bound(n, a, c));
  EXPECT_NEAR(oscillation(sinusoid(n, 31, a, c), kHandCutoff_hz, kT).rms_above_N.value, a / std::sqrt(2.0),
              rms_bound(n, a, c));
}

TEST(Oscillation, FewerTicksThanOneCutoffPeriodSayWhy) {
  // 1/(30 Hz · 1 ms) = 33.3 ticks: 34 are needed for a bin at or below 30 Hz besides the mean.
  EXPECT_EQ(oscillation_min_ticks(kHandCutoff_hz, kT), 34u);
  EXPECT_EQ(oscillation_min_ticks(25.0, kT), 40u);  // a whole number stays itself
  const Oscillation short_one = oscillation(std::vector<double>(33, 1.0), kHandCutoff_hz, kT);
  EXPECT_FALSE(short_one.rms_above_N.available());
  EXPECT_EQ(short_one.rms_above_N.unavailable,
            "a contact of 33 ticks is shorter than one period of the 30 Hz cutoff (34 ticks): every frequency it "
            "resolves but its mean lies above");
  const Oscillation constant = oscillation(std::vector<double>(34, 1.0), kHandCutoff_hz, kT);
  EXPECT_EQ(constant.rms_above_N.value, 0.0);  // the exact transform of a constant is N·C in bin 0 alone
  EXPECT_EQ(constant.share_above.unavailable, "the force is constant: it has no oscillation to share");
}

// --- Energy: a spring held through each tick, and one a tick late --------------------------------

// The tip presses straight in by δ a tick for N ticks and comes back out the same way: penetration
// p_n = n·δ (n ≤ N), (2N − n)·δ (n ≥ N), the tip at z_n = −p_n (the surface at z = 0), 2N holds.
struct InAndOut {
  std::vector<Eigen::Vector3d> position;  // z_0 … z_2N
  std::vector<double> depth;              // p_0 … p_2N
};
InAndOut in_and_out(int n, double delta) {
  InAndOut m;
  for (int j = 0; j <= 2 * n; ++j) {
    m.depth.push_back(double(j <= n ? j : 2 * n - j) * delta);
    m.position.emplace_back(0, 0, -m.depth.back());
  }
  return m;
}

// The rounding of M: each z_n = −n·δ is within ε·Nδ/2, so each Δz within ε·Nδ of δ (relative N·ε);
// a D term (a square) is within (2N + 3)·ε of its value, a W term within (N + 2)·ε; the running sum
// of 2N terms adds at most 2N·ε·Σ|terms|. So |M − M_exact| ≤ (4N + 3)·ε·Σ|terms|.
double margin_bound(int n, double sum_of_terms) { return (4.0 * n + 3) * kEps * sum_of_terms; }

TEST(EnergyMargin, ASpringHeldThroughEachTickReturnsHalfKDeltaSquaredATick) {
  // F_j = k·p_j held while the tip moves δ: going in the force is a step behind (it does −k·p_j·δ,
  // less than the spring takes), coming out a step ahead. W = kδ·(Σ_{j≥N} p_j − Σ_{j<N} p_j) =
  // kδ²·(N(N+1)/2 − N(N−1)/2) = N·k·δ², k·δ²/2 a tick: Colgate & Schenkel's excess of the
  // sampled spring. D = 2N·B·δ²/T. M = 2N·B·δ²/T − N·k·δ², positive iff B > k·T/2.
  const int n = 100;
  const double delta = 1e-5, k = 500, b_device = 1.5;  // 10 mm/s; k·T/2 = 0.25 < B
  const InAndOut m = in_and_out(n, delta);
  std::vector<double> f;
  for (int j = 0; j < 2 * n; ++j) f.push_back(k * m.depth[j]);
  const EnergyMargin e = energy_margin(m.position, along_z(f), b_device, kT);
  const double dissipated = 2 * n * b_device * delta * delta / kT;
  const double work = n * k * delta * delta;
  const double sum_of_terms = dissipated + k * delta * delta * n * n;  // Σ|W_j| = kδ·Σp_j = kδ²·N²
  ASSERT_EQ(e.after_tick_J.size(), std::size_t(2 * n));
  EXPECT_NEAR(e.end_J, dissipated - work, margin_bound(n, sum_of_terms));
  EXPECT_GT(e.end_J, 0.0);
}

TEST(EnergyMargin, ASpringATickLateInjectsEnergyAndItsWorstTickIsTheLast) {
  // The same motion, the force a tick late: F_j = k·p_{j−1} (p_{−1} = 0). In: Σ_{j<N} p_{j−1} =
  // δ·(N−1)(N−2)/2; out: Σ_{j=N}^{2N−1} p_{j−1} = δ·((N−1) + N(N+1)/2 − 1). W = kδ²·(3N − 3), three
  // times the held spring's: M = 2N·B·δ²/T − 3(N − 1)·k·δ², negative here (k = 1500 N/m: 300 vs 445.5
  // in units of k·δ²/1000). Every hold coming out lowers M (k·p_{j−1}·δ ≥ 2k·δ² > B·δ²/T, as
  // 2kT = 3 > B = 1.5) and every hold going in raises it from M(0) = B·δ²/T > 0, so the worst is the
  // last hold, tick 2N − 1, and equals M.
  const int n = 100;
  const double delta = 1e-5, k = 1500, b_device = 1.5;
  const InAndOut m = in_and_out(n, delta);
  std::vector<double> f{0.0};
  for (int j = 1; j < 2 * n; ++j) f.push_back(k * m.depth[j - 1]);
  const EnergyMargin e = energy_margin(m.position, along_z(f), b_device, kT);
  const double expected = 2 * n * b_device * delta * delta / kT - 3.0 * (n - 1) * k * delta * delta;
  const double sum_of_terms = 2 * n * b_device * delta * delta / kT + k * delta * delta * n * n;
  EXPECT_LT(expected, 0.0);
  EXPECT_NEAR(e.end_J, expected, margin_bound(n, sum_of_terms));
  ASSERT_TRUE(e.worst_J.available());
  EXPECT_EQ(e.worst_tick, std::size_t(2 * n - 1));
  EXPECT_EQ(e.worst_J.value, e.end_J);
}

TEST(EnergyMargin, NoCompletedHoldHasNoWorstTick) {
  // The run ended on the contact's first tick: one position, no hold.
  const EnergyMargin e = energy_margin({Eigen::Vector3d(0, 0, 0.1)}, {Eigen::Vector3d(0, 0, 1)}, 1.5, kT);
  EXPECT_TRUE(e.after_tick_J.empty());
  EXPECT_EQ(e.end_J, 0.0);
  EXPECT_EQ(e.worst_J.unavailable, "no tick's hold has completed: the run ended on the contact's first tick");
}

// --- The clamp and the overshoot -------------------------------------------------------------------

TEST(ForceLimit, TicksAtTheCapAreThoseWhoseSpringReachesIt) {
  // f = min(k·n·δ, 8 N) with k·δ = 0.05 N a tick: at the cap from n = 160 on: 40 of 200 ticks. A
  // mesh's f·n̂ is within a few ulps of the cap: 8·(1 − 4ε) still counts, 8·(1 − 16ε) does not.
  std::vector<double> f;
  for (int n = 0; n < 200; ++n) f.push_back(std::min(500.0 * n * 1e-4, 8.0));
  EXPECT_EQ(ticks_at_force_limit(f, 8.0), 40);
  EXPECT_EQ(ticks_at_force_limit({8.0 * (1 - 4 * kEps), 8.0 * (1 - 16 * kEps)}, 8.0), 1);
}

TEST(Overshoot, IsTheMostTheForceExceedsTheSpringAtItsDepth) {
  // Spring k·p plus a push of 0.1 N on one tick; at the cap (8 N for a 10 N spring) nothing exceeds it.
  const double k = 500;
  const std::vector<double> depth{0.001, 0.002, 0.02, 0.002};
  const std::vector<double> force{0.5, 1.1, 8.0, 0.9};
  EXPECT_NEAR(overshoot_N(force, depth, k), 0.1, 4 * kEps);  // 1.1 − 500·0.002, rounded twice
  EXPECT_EQ(overshoot_N({0.4}, {0.001}, k), 0.0);            // below the spring: none
}

}  // namespace
}  // namespace bleedsim
