// Convergence ladders (core/study/ladder.cpp) on ensembles whose convergence is known by
// construction: q(h) = q* + C·hᵖ, with the seeds' noise the same at every level (differences exact)
// or drawn afresh at each (differences in the noise); the observed order, Richardson's
// extrapolation and the asymptotic test against them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/study/ladder.h"

namespace bleedsim {
namespace {

TEST(ObservedOrder, RecoversThePowerOfAnExactLadder) {
  // Differences C·(h0ᵖ − h1ᵖ) and C·(h1ᵖ − h2ᵖ), on a constant ratio and on an uneven one; the
  // bisection stops at 1e-13.
  for (const double p : {-1.0, 0.5, 1.0, 2.0, 4.0})
    for (const auto& h : {std::vector<double>{4, 2, 1}, std::vector<double>{2, 1.4, 1}, std::vector<double>{1, 0.3, 0.25}}) {
      const double ratio = (std::pow(h[0], p) - std::pow(h[1], p)) / (std::pow(h[1], p) - std::pow(h[2], p));
      EXPECT_NEAR(observed_order(h[0], h[1], h[2], ratio), p, 1e-9) << p << " on " << h[0] << ", " << h[1] << ", " << h[2];
    }
  // Constant ratio r: log(ratio)/log(r).
  EXPECT_NEAR(observed_order(1, 0.5, 0.25, 3.0), std::log(3.0) / std::log(2.0), 1e-12);
  // p → 0 on a ratio of 2: the ratio of the logarithms' steps, 1.
  EXPECT_NEAR(observed_order(4, 2, 1, 1.0), 0.0, 1e-12);
  // Not a ladder: a level without a step, or steps out of order.
  EXPECT_TRUE(std::isnan(observed_order(INFINITY, 1, 0.5, 2)));
  EXPECT_TRUE(std::isnan(observed_order(1, 2, 0.5, 2)));
}

TEST(Richardson, ExtrapolatesAnExactLadderToItsLimit) {
  // q = 3 + 0.7·h²: from h = 0.5 and 0.25, q* = q_f − (q_c − q_f)·w with w = 1/(2² − 1) = 1/3.
  const auto q = [](double h) { return 3.0 + 0.7 * h * h; };
  const double w = richardson_weight(0.5, 0.25, 2.0);
  EXPECT_NEAR(w, 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(q(0.25) - (q(0.5) - q(0.25)) * w, 3.0, 1e-15);
  // Uneven steps: w = h_fᵖ/(h_cᵖ − h_fᵖ).
  EXPECT_NEAR(richardson_weight(1.4, 1.0, 1.5), 1.0 / (std::pow(1.4, 1.5) - 1.0), 1e-14);
}

// Levels q(h) per seed and component: q* + C_c·hᵖ + noise, the noise fixed per (seed, component)
// when `common`, else drawn per level too.
std::vector<SeedValues> ladder_values(const std::vector<double>& steps, double p, double noise, bool common,
                                      std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  const auto draw = [&] { return noise * (double(engine() >> 11) / 9007199254740992.0 - 0.5); };
  const int seeds = 6, components = 5;
  SeedValues shared(seeds, std::vector<double>(components));
  for (auto& s : shared)
    for (double& v : s) v = draw();
  std::vector<SeedValues> levels;
  for (const double h : steps) {
    SeedValues level(seeds, std::vector<double>(components));
    for (int s = 0; s < seeds; ++s)
      for (int c = 0; c < components; ++c)
        level[std::size_t(s)][std::size_t(c)] =
            1.0 + (0.5 + 0.1 * c) * std::pow(h, p) + (common ? shared[std::size_t(s)][std::size_t(c)] : draw());
    levels.push_back(level);
  }
  return levels;
}

LadderFit fit(const std::vector<double>& steps, const std::vector<SeedValues>& levels) {
  LadderInput in{steps, {}, {}};
  for (std::size_t i = 0; i < steps.size(); ++i) {
    in.labels.push_back("h=" + std::to_string(steps[i]));
    in.levels.push_back(&levels[i]);
  }
  return fit_ladder(in);
}

TEST(LadderFit, AnExactLadderIsAsymptoticAtItsOrder) {
  // The seeds move every level alike: each difference is C·(hᵢᵖ − hᵢ₊₁ᵖ) exactly in every seed,
  // every order estimate is p (to the rounding of a few operations on values near 1: 1e-9), and
  // the intervals have no width, so they agree.
  const std::vector<double> steps = {8, 4, 2, 1};
  const LadderFit f = fit(steps, ladder_values(steps, 1.5, 0.3, true, 1));
  ASSERT_EQ(f.orders.size(), 2u);
  for (const Estimate& order : f.orders) EXPECT_NEAR(order.value, 1.5, 1e-9);
  EXPECT_EQ(f.asymptotic_from, 0);
  EXPECT_NEAR(f.order, 1.5, 1e-9);
  EXPECT_EQ(f.statement.rfind("asymptotic from h=8", 0), 0u) << f.statement;
}

TEST(LadderFit, DifferencesInTheNoiseAreSaidToBe) {
  // The levels differ by C·(hᵢᵖ − hᵢ₊₁ᵖ) ≤ 0.9·(0.01² − 0.005²) = 7e-5, and each level draws its
  // own noise of ±0.5 (σ = 0.29): no difference stands out, and the statement says so.
  const std::vector<double> steps = {0.02, 0.01, 0.005};
  const LadderFit f = fit(steps, ladder_values(steps, 2.0, 1.0, false, 2));
  EXPECT_EQ(f.asymptotic_from, -1);
  EXPECT_NE(f.statement.find("within the seeds' noise"), std::string::npos) << f.statement;
}

TEST(LadderFit, AMetricTheKnobDoesNotMoveIsSaidToBeUnchanged) {
  // Every level the same values (a knob that leaves the metric alone, as the blur leaves the stain).
  const std::vector<double> steps = {4, 2, 1};
  const std::vector<SeedValues> same(3, SeedValues{{1.0, 2.0}, {1.5, 2.5}, {0.5, 3.0}});
  const LadderFit f = fit(steps, same);
  EXPECT_EQ(f.asymptotic_from, -1);
  EXPECT_EQ(f.statement, "unchanged: every level gives the same (the knob does not move it)");
}

TEST(LadderFit, GrowingDifferencesAreNotAsymptotic) {
  // p = −1: the differences grow as the steps shrink (order −1, its interval of no width).
  const std::vector<double> steps = {4, 2, 1};
  const LadderFit f = fit(steps, ladder_values(steps, -1.0, 0.3, true, 3));
  EXPECT_EQ(f.asymptotic_from, -1);
  EXPECT_NEAR(f.orders[0].value, -1.0, 1e-9);
  EXPECT_NE(f.statement.find("do not shrink"), std::string::npos) << f.statement;
  // Two levels: one difference, no order.
  const LadderFit two = fit({2, 1}, ladder_values({2, 1}, 1.0, 0.3, true, 4));
  EXPECT_TRUE(two.orders.empty());
  EXPECT_NE(two.statement.find("needs three levels"), std::string::npos) << two.statement;
}

TEST(LadderFit, TheRangeStartsWhereTheOrdersAgree) {
  // Exact levels whose coarse end is off the power law (q at h = 16 pushed up by 5): the order from
  // the coarsest three disagrees with the next, so the asymptotic range starts at h = 8.
  const std::vector<double> steps = {16, 8, 4, 2};
  std::vector<SeedValues> levels = ladder_values(steps, 2.0, 0.3, true, 5);
  for (auto& seed : levels[0])
    for (double& v : seed) v += 5.0;
  const LadderFit f = fit(steps, levels);
  EXPECT_EQ(f.asymptotic_from, 1) << f.statement;
  EXPECT_NEAR(f.order, 2.0, 1e-9);
}

}  // namespace
}  // namespace bleedsim
