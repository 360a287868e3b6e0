#pragma once
// Statistics over an ensemble of runs that differ only in their seed (docs/accuracy.md, "Ensembles"):
// the runs are independent draws, so a mean over them has a Student t interval, and a statistic
// that is not a mean (a distance between two ensembles' means, a seed spread) has a jackknife one.
// Every interval is 95 % and two-sided. Loops run in a fixed order: the same values give the same
// bits.
#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

namespace bleedsim {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The 97.5 % quantile of Student's t with `dof` degrees of freedom: a 95 % interval is
// mean ± t · standard error. Computed from the t distribution's CDF (the regularised incomplete
// beta function) by bisection, to 1e-12.
double student_t_975(int dof);

// A value and its 95 % confidence interval [lo, hi]; NaN where it cannot be had (too few seeds).
struct Estimate {
  double value = kNaN, lo = kNaN, hi = kNaN;
  double half_width() const { return (hi - lo) / 2; }
};

// The mean of independent values with its Student t interval (n − 1 degrees of freedom); no
// interval for fewer than two.
Estimate mean_ci(const std::vector<double>& values);

// The jackknife (Quenouille–Tukey) interval of a statistic of n seeds: `full` is its value on all
// of them, `leave_out(i)` its value without seed i. Standard error
// √((n − 1)/n · Σ (θ₍ᵢ₎ − θ̄)²), interval full ± t(n − 1) · error (Efron & Tibshirani 1993, §11);
// none for fewer than two seeds or where a leave-out is not finite (a variance left with one seed).
// For a mean it is exactly the Student t interval.
Estimate jackknife_ci(std::size_t n, double full, const std::function<double(std::size_t)>& leave_out);

// One metric of one setting: per seed (outer), its components (frames of a curve, cells of a
// field at the snapshot frames, columns of a profile), the same count in every seed.
using SeedValues = std::vector<std::vector<double>>;

// The distance between two settings' ensemble means, the seeds' noise taken out. With d = x − y
// paired by seed (both settings run on the same seeds, which are independent of one another),
// E[d̄²] = δ² + σ_d²/n for each component, so d̄² − s_d²/n is an unbiased estimate of the squared
// difference of the means δ². Averaged over the components and square-rooted (0 where the
// estimate is negative: within the noise): an RMS distance, with its jackknife interval.
// `squared` keeps the unclamped mean-square estimate (negative: within the noise).
struct Distance {
  Estimate rms;                        // √ of the clamped estimate, and of its interval's ends
  Estimate squared;                    // the mean-square estimate itself and its interval
  std::vector<double> squared_without;  // the estimate with seed i left out (NaN below three seeds)
};
Distance ensemble_distance(const SeedValues& x, const SeedValues& y);

// The seed-to-seed spread: the RMS distance between two runs that differ only in their seed,
// √(2 · mean over the components of the unbiased variance over the seeds) (E[(xᵢ − xⱼ)²] = 2σ²),
// with its jackknife interval.
Estimate seed_spread(const SeedValues& x);

// The mean over pairs of seeds i < j of f(i, j) (a distance between two runs of the same setting
// that differ only in their seed), with its jackknife interval (seed i left out: the pairs without it).
Estimate pair_mean(std::size_t n, const std::function<double(std::size_t, std::size_t)>& f);

}  // namespace bleedsim
