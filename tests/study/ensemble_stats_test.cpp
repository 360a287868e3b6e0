// The ensemble statistics (core/study/ensemble_stats.cpp) against what theory says of them: Student's
// t quantiles, the mean's interval and its coverage, the jackknife of a mean (exactly the t
// interval), the distance between ensemble means with the noise taken out (unbiased), the seed
// spread, and the mean over pairs of seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/study/ensemble_stats.h"

namespace bleedsim {
namespace {

// Standard normal draws by Box–Muller from a portable engine (the same numbers on every machine).
struct Normal {
  std::mt19937_64 engine;
  explicit Normal(std::uint64_t seed) : engine(seed) {}
  double operator()() {
    const double u = (double(engine() >> 11) + 0.5) / 9007199254740992.0;
    const double v = double(engine() >> 11) / 9007199254740992.0;
    return std::sqrt(-2 * std::log(u)) * std::cos(2 * M_PI * v);
  }
};

TEST(StudentT, QuantilesMatchTheDistribution) {
  // scipy.stats.t.ppf(0.975, dof) (SciPy 1.10). The bisection stops at 1e-12, and the continued
  // fraction converges to 1e-15 relative: 1e-9 holds both.
  const struct {
    int dof;
    double t;
  } table[] = {{1, 12.706204736432095}, {2, 4.302652729911275},  {3, 3.182446305284263},
               {4, 2.7764451051977987}, {7, 2.3646242510102993}, {10, 2.2281388519649385},
               {30, 2.0422724563012373}, {100, 1.9839715184496334}, {1000000, 1.9599663568141066}};
  for (const auto& row : table) EXPECT_NEAR(student_t_975(row.dof), row.t, 1e-9) << row.dof;
  EXPECT_TRUE(std::isnan(student_t_975(0)));
}

TEST(MeanCi, TheStudentIntervalByHand) {
  // 1, 2, 3, 4: mean 2.5, s² = 5/3, standard error √(5/12), interval ± t(3) · √(5/12).
  const Estimate e = mean_ci({1, 2, 3, 4});
  EXPECT_DOUBLE_EQ(e.value, 2.5);
  EXPECT_NEAR(e.half_width(), 3.182446305284263 * std::sqrt(5.0 / 12.0), 1e-9);
  EXPECT_TRUE(std::isnan(mean_ci({7}).lo));  // one value: a mean, no interval
  EXPECT_DOUBLE_EQ(mean_ci({7}).value, 7);
}

TEST(MeanCi, CoversTheMeanNineteenTimesInTwenty) {
  // For normal data the t interval covers the true mean with probability exactly 0.95. Over 4000
  // ensembles of 4 (and of 8) the observed coverage has a standard error √(0.95 · 0.05 / 4000) =
  // 0.0034; four of them: 0.0138.
  for (const int n : {4, 8}) {
    Normal normal(n);
    int covered = 0;
    const int trials = 4000;
    for (int trial = 0; trial < trials; ++trial) {
      std::vector<double> values;
      for (int i = 0; i < n; ++i) values.push_back(3.0 + 0.5 * normal());
      const Estimate e = mean_ci(values);
      covered += e.lo <= 3.0 && 3.0 <= e.hi;
    }
    EXPECT_NEAR(double(covered) / trials, 0.95, 0.0138) << n << " seeds";
  }
}

TEST(Jackknife, OfAMeanIsTheStudentInterval) {
  // θ = mean: θ₍ᵢ₎ − θ̄ = −(xᵢ − x̄)/(n − 1), so √((n − 1)/n · Σ(θ₍ᵢ₎ − θ̄)²) = s/√n, and the
  // interval, with t(n − 1), is mean_ci's.
  const std::vector<double> x = {0.3, 1.7, -0.4, 2.2, 0.9, 1.1};
  double sum = 0;
  for (const double v : x) sum += v;
  const Estimate jack = jackknife_ci(x.size(), sum / double(x.size()),
                                     [&](std::size_t i) { return (sum - x[i]) / double(x.size() - 1); });
  const Estimate t = mean_ci(x);
  EXPECT_NEAR(jack.value, t.value, 1e-15);
  EXPECT_NEAR(jack.lo, t.lo, 1e-12);
  EXPECT_NEAR(jack.hi, t.hi, 1e-12);
  EXPECT_TRUE(std::isnan(jackknife_ci(3, 1.0, [](std::size_t) { return NAN; }).lo));
}

TEST(EnsembleDistance, TakesTheSeedsNoiseOutWithoutBias) {
  // x = δ + noise, y = noise' (independent, σ = 1), 4 seeds, 3 components with δ = (0.2, −0.5, 0.1):
  // E[d̄²] = δ² + 2σ²/4 per component, so the raw mean square of the mean difference is biased by
  // 0.5 and the estimate is not: over 4000 draws each mean is within 4 of its own standard errors
  // of mean(δ²) = 0.1 (raw: 0.6).
  const std::vector<double> delta = {0.2, -0.5, 0.1};
  double delta_squared = 0;
  for (const double d : delta) delta_squared += d * d / 3;
  Normal normal(11);
  const int trials = 4000, seeds = 4;
  std::vector<double> estimates, raws;
  for (int trial = 0; trial < trials; ++trial) {
    SeedValues x(seeds, std::vector<double>(3)), y = x;
    for (int s = 0; s < seeds; ++s)
      for (int c = 0; c < 3; ++c) {
        x[std::size_t(s)][std::size_t(c)] = delta[std::size_t(c)] + normal();
        y[std::size_t(s)][std::size_t(c)] = normal();
      }
    estimates.push_back(ensemble_distance(x, y).squared.value);
    double raw = 0;
    for (int c = 0; c < 3; ++c) {
      double mean = 0;
      for (int s = 0; s < seeds; ++s) mean += (x[std::size_t(s)][std::size_t(c)] - y[std::size_t(s)][std::size_t(c)]) / seeds;
      raw += mean * mean / 3;
    }
    raws.push_back(raw);
  }
  const Estimate e = mean_ci(estimates), r = mean_ci(raws);
  const double e_error = e.half_width() / student_t_975(trials - 1), r_error = r.half_width() / student_t_975(trials - 1);
  EXPECT_NEAR(e.value, delta_squared, 4 * e_error);
  EXPECT_NEAR(r.value, delta_squared + 2.0 / seeds, 4 * r_error);
}

TEST(EnsembleDistance, IsExactWhenTheSeedsMoveBothAlike) {
  // The same noise in both (a knob that leaves the particles alone): the differences are δ in every
  // seed, their variance 0, and the distance is |δ| exactly, its interval of no width.
  SeedValues x = {{1.0, 5.0}, {2.0, 7.0}, {4.0, 6.0}}, y = x;
  for (auto& seed : x) seed[0] += 0.25, seed[1] -= 0.25;
  const Distance d = ensemble_distance(x, y);
  EXPECT_DOUBLE_EQ(d.rms.value, 0.25);
  EXPECT_DOUBLE_EQ(d.rms.lo, 0.25);
  EXPECT_DOUBLE_EQ(d.rms.hi, 0.25);
  EXPECT_EQ(d.squared_without.size(), 3u);
  // Unequal shapes are refused.
  EXPECT_THROW(ensemble_distance(x, {{1.0}, {2.0}, {3.0}}), std::invalid_argument);
}

TEST(SeedSpread, IsTheRmsDistanceBetweenTwoSeedsRuns) {
  // Component c takes a_c · (−1, 1, −1, 1) over four seeds: its unbiased variance is a_c² · 4/3, and
  // two runs differ by 2σ² in the mean square, so the spread is √(2 · 4/3 · mean a_c²) with
  // a = (1, 2): √(20/3). (Directly: of the six pairs of seeds, four differ by 2a_c and two by 0, a
  // mean square of 8/3 · a_c² — the variance's 4/3 · 2 — taken without bias over the seeds.)
  const SeedValues x = {{-1, -2}, {1, 2}, {-1, -2}, {1, 2}};
  EXPECT_NEAR(seed_spread(x).value, std::sqrt(20.0 / 3.0), 1e-14);
  EXPECT_TRUE(std::isnan(seed_spread({{1.0}}).value));  // one seed has no spread
}

TEST(PairMean, OverEveryPairAndWithEachSeedLeftOut) {
  // f = |i − j| over 4 seeds: the pairs give 1, 2, 3, 1, 2, 1, mean 10/6. Left out: seed 0 leaves
  // (1,2,1) → 4/3, seed 1 (2,3,1) → 2, seed 2 (1,3,2) → 2, seed 3 (1,2,1) → 4/3; mean 5/3, squares
  // 4 · (1/3)², error √(3/4 · 4/9) = 1/√3.
  const Estimate e = pair_mean(4, [](std::size_t i, std::size_t j) { return std::abs(double(i) - double(j)); });
  EXPECT_NEAR(e.value, 10.0 / 6.0, 1e-15);
  EXPECT_NEAR(e.half_width(), 3.182446305284263 / std::sqrt(3.0), 1e-9);
  EXPECT_TRUE(std::isnan(pair_mean(2, [](std::size_t, std::size_t) { return 1.0; }).lo));
}

}  // namespace
}  // namespace bleedsim
