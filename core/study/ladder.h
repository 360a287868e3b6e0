#pragma once
// A convergence ladder (docs/accuracy.md, "Ladders"): one knob's levels from coarse to fine, every
// other knob at the reference's setting, each level an ensemble over the same seeds. What the
// successive differences say: the observed order where the ladder is in its asymptotic range, and
// Richardson's extrapolation there; a plain statement where it is not.
#include <string>
#include <vector>

#include "core/study/ensemble_stats.h"

namespace bleedsim {

// The order p for which a ladder of step sizes h0 > h1 > h2 with an error C·hᵖ would have successive
// differences in the ratio |q(h0) − q(h1)| / |q(h1) − q(h2)| = (h0ᵖ − h1ᵖ) / (h1ᵖ − h2ᵖ), which rises
// with p from 0 (p → −∞) to ∞: found by bisection on [−20, 20] (clamped there). For a constant
// refinement ratio r = h0/h1 = h1/h2 it is log(ratio)/log(r).
double observed_order(double h0, double h1, double h2, double ratio);

// Richardson's extrapolation from a coarse and a fine level: with q(h) = q* + C·hᵖ,
// q* = q_fine − (q_coarse − q_fine) · w, w = h_fineᵖ / (h_coarseᵖ − h_fineᵖ) (1/(rᵖ − 1) for a ratio r).
// w is also the fine level's distance from the limit in units of the last difference.
double richardson_weight(double h_coarse, double h_fine, double p);

struct LadderInput {
  std::vector<double> step;                 // h per level, coarse to fine: the knob's step size
  std::vector<std::string> labels;          // each level's value, as the statement names it
  std::vector<const SeedValues*> levels;    // the metric at each level (the same seeds, in order)
};

struct LadderFit {
  std::vector<Distance> differences;  // between level i and i + 1: the ensemble means' distance
  std::vector<Estimate> orders;       // from differences i and i + 1 (jackknifed over the seeds)
  int asymptotic_from = -1;           // the first level of the asymptotic range; −1: none
  double order = kNaN;                // where asymptotic: the finest order estimate (Richardson's)
  std::string statement;              // what the ladder says, in words
};

// The ladder is in its asymptotic range from level a when, from there to the finest level,
//   (1) every difference is above the seeds' noise (its interval's lower end is above 0),
//   (2) every order estimate is positive (its interval's lower end above 0: the differences shrink),
//   (3) consecutive order estimates agree (their intervals overlap).
// The range is the longest such run of levels that ends at the finest; it needs three levels.
LadderFit fit_ladder(const LadderInput& input);

}  // namespace bleedsim
