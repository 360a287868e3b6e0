// The blood model converges as it is refined: a ladder of particle sizes and a ladder of time steps
// on a small scene, each level an ensemble over 64 seeds (the flow is chaotic: one seed's drops fall
// where its rounding sends them, so runs are compared as ensembles, never one by one).
//
// A cut 1 mm above the floor of a 6 × 4 mm panel bleeds 1 mm³ for half a second; after 2 s the
// blood has welled up, run down and come to rest in a pool. Two outcomes are compared between
// successive levels:
//   * the film: the ensemble-mean thickness averaged over 0.5 mm blocks, RMS over the blocks;
//   * the pile height: the ensemble-mean height of the blood's centroid above the floor.
// The seeds' noise is taken out of each difference (difference() below), and reported beside it.
//
// Particle size (d = 0.8, 0.4, 0.2 mm: the default's 0.2 × 4, 2, 1; the flow of blood kept): a
// consistent discretisation's differences fall by r^p for a refinement by r = 2; the test asserts
// that the first is above the noise (the ladder resolves something) and that each is smaller than
// the last, and reports the observed order p = log(e₁/e₂)/log(r). (A ladder in steps of √2 was
// tried first: its successive differences are closer than their own uncertainty, 1–2 µm, so which
// is smaller was a coin toss.)
//
// Time step (the fewest stable sub-steps × 1, 2, 4, 8, at d = 0.4): the contact's stability limit
// keeps the step so far below the flow's time scales that no difference stands out of the noise even
// at the coarsest step; the test asserts exactly that (each within twice its noise), which fails if
// the step mattered at the scale the ensemble resolves. (The integrator's own first order is shown
// on the lone particle, against its closed form: particle_physics_test.cpp. The model has no
// solver iterations: one neighbour pass a step.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "core/effects/cuts.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/runtime/tissue.h"
#include "core/simulation/simulation.h"
#include "core/study/study_knobs.h"
#include "tests/runtime/field_values.h"

namespace bleedsim {
namespace {

constexpr int kSeeds = 64;
constexpr double kBlockMm = 0.5;

Scene small_scene(std::uint64_t seed) {
  Scene scene;
  scene.name = "convergence";
  scene.domain = Domain{120, 80, 6.0, 4.0};
  scene.duration_s = 2.0;
  scene.frame_rate_hz = 30.0;
  scene.seed = seed;
  scene.tissue = procedural_tissue(scene.domain.width_px, scene.domain.height_px, 1);
  scene.effects.set(ParticleParams{});
  Cut cut = cut_at(scene, 3.0, 3.0, 0.0);
  cut.bleed_s = 0.5;
  scene.cuts.push_back(cut);
  return scene;
}

struct Outcome {
  std::vector<double> film;  // mean thickness per block, mm
  double pile_height = 0;    // the blood's centroid above the floor, mm
};


Outcome run(const Scene& scene) {
  Simulation sim(scene, BackendChoice{BackendChoice::Want::cpu, 2});
  while (sim.frames_done() < scene.frame_count()) sim.step();
  Outcome out;
  const Domain& d = scene.domain;
  const int bx = int(std::lround(d.width_mm / kBlockMm)), by = int(std::lround(d.height_mm / kBlockMm));
  const int px = d.width_px / bx, py = d.height_px / by;
  const std::vector<float> film = test::field_values<float>(sim, "splat/thickness");
  out.film.assign(std::size_t(bx * by), 0.0);
  for (int y = 0; y < d.height_px; ++y)
    for (int x = 0; x < d.width_px; ++x)
      out.film[std::size_t((y / py) * bx + x / px)] += film[std::size_t(y * d.width_px + x)] / (px * py);
  const ParticleModel m = resolve_particles(scene).model;
  const std::vector<float> position = test::field_values<float>(sim, "particles/position");
  const std::vector<std::uint32_t> age = test::field_values<std::uint32_t>(sim, "particles/age");
  double sum = 0;
  int n = 0;
  for (std::size_t s = 0; s < age.size(); ++s)
    if (is_alive(m, age[s])) sum += d.height_mm - position[2 * s + 1], ++n;
  out.pile_height = sum / std::max(n, 1);
  return out;
}

// A level's runs, one per seed.
using Level = std::vector<Outcome>;

template <class Refine>
Level ensemble(Refine refine, int first_seed = 1) {
  Level level;
  for (int seed = first_seed; seed < first_seed + kSeeds; ++seed) {
    Scene scene = small_scene(std::uint64_t(seed));
    refine(scene);
    level.push_back(run(scene));
  }
  return level;
}

// Mean and variance of the ensemble mean of one value over a level's runs.
template <class Get>
std::pair<double, double> mean_and_error(const Level& level, Get get) {
  double mean = 0, var = 0;
  for (const Outcome& o : level) mean += get(o) / level.size();
  for (const Outcome& o : level) var += (get(o) - mean) * (get(o) - mean) / (level.size() - 1);
  return {mean, var / level.size()};
}

// The systematic difference between two levels, with the seeds' noise taken out: for ensemble
// means Ā, B̄ of n runs, E[(Ā − B̄)²] = (μ_A − μ_B)² + (σ_A² + σ_B²)/n, so subtracting the
// sample variances of the means leaves an unbiased estimate of (μ_A − μ_B)². Summed over the
// values compared and square-rooted: an RMS difference, and beside it the noise it was cleared of.
struct Difference {
  double systematic = 0, noise = 0;
};

template <class Get>
Difference difference(const Level& a, const Level& b, std::size_t values, Get get) {
  double squared = 0, noise = 0;
  for (std::size_t i = 0; i < values; ++i) {
    const auto [ma, va] = mean_and_error(a, [&](const Outcome& o) { return get(o, i); });
    const auto [mb, vb] = mean_and_error(b, [&](const Outcome& o) { return get(o, i); });
    squared += (ma - mb) * (ma - mb) - va - vb;
    noise += va + vb;
  }
  return {std::sqrt(std::max(squared, 0.0) / values), std::sqrt(noise / values)};
}

Difference film_difference(const Level& a, const Level& b) {
  return difference(a, b, a.front().film.size(), [](const Outcome& o, std::size_t i) { return o.film[i]; });
}
Difference height_difference(const Level& a, const Level& b) {
  return difference(a, b, 1, [](const Outcome& o, std::size_t) { return o.pile_height; });
}

struct Ladder {
  std::vector<Difference> film, height;  // between level i and i + 1
};

// Runs each level's ensemble, and reports every level's pile height and every difference, with the
// observed order where two successive differences stand out of the noise.
template <class Refine>
Ladder climb(const char* what, const std::vector<double>& values, double ratio, Refine refine) {
  std::vector<Level> levels;
  for (const double v : values) levels.push_back(ensemble([&](Scene& s) { refine(s, v); }));
  Ladder ladder;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const auto [h, var] = mean_and_error(levels[i], [](const Outcome& o) { return o.pile_height; });
    std::cout << what << " " << values[i] << ": pile height " << h << " ± " << std::sqrt(var) << " mm" << std::endl;
    if (i == 0) continue;
    ladder.film.push_back(film_difference(levels[i - 1], levels[i]));
    ladder.height.push_back(height_difference(levels[i - 1], levels[i]));
    std::cout << "  from " << values[i - 1] << ": film " << 1e3 * ladder.film.back().systematic << " µm RMS (noise "
              << 1e3 * ladder.film.back().noise << "), pile height " << 1e3 * ladder.height.back().systematic
              << " µm (noise " << 1e3 * ladder.height.back().noise << ")";
    if (i >= 2) {
      const auto order = [&](const std::vector<Difference>& e) {
        const Difference& coarse = e[i - 2];
        const Difference& fine = e[i - 1];
        if (fine.systematic <= fine.noise) return std::string("in the noise");
        return std::to_string(std::log(coarse.systematic / fine.systematic) / std::log(ratio));
      };
      std::cout << "; observed order: film " << order(ladder.film) << ", pile height " << order(ladder.height);
    }
    std::cout << std::endl;
  }
  return ladder;
}

void expect_shrinking(const char* what, const std::vector<Difference>& e) {
  EXPECT_GT(e.front().systematic, 2.0 * e.front().noise) << what << ": the coarsest levels differ by no more than the noise";
  for (std::size_t i = 1; i < e.size(); ++i)
    EXPECT_LT(e[i].systematic, e[i - 1].systematic) << what << ": difference " << i << " grew";
}

TEST(ParticleConvergence, FilmAndPileConvergeAsTheParticlesShrink) {
  // Each size at the fewest sub-steps its own contact allows (the knob alone would hold the time
  // step; the next test shows the fewest stable sub-steps are converged).
  const Ladder ladder = climb("particle size", {4.0, 2.0, 1.0}, 2.0, [](Scene& s, double f) {
    find_knob("particle_size")->apply(s, f);
    s.effects.get<ParticleParams>().substeps = 0;
  });
  expect_shrinking("film", ladder.film);
  expect_shrinking("pile height", ladder.height);
}

TEST(ParticleConvergence, TheFewestStableSubStepsAreAlreadyConverged) {
  const auto coarse = [](Scene& s) {
    find_knob("particle_size")->apply(s, 2.0);
    s.effects.get<ParticleParams>().substeps = 0;  // the fewest this size's contact allows
  };
  Scene base = small_scene(1);
  coarse(base);
  const double fewest = find_knob("substeps")->base(base);
  const Ladder ladder = climb("sub-steps ×", {1.0, 2.0, 4.0, 8.0}, 2.0, [&](Scene& s, double f) {
    coarse(s);
    find_knob("substeps")->apply(s, f * fewest);
  });
  for (std::size_t i = 0; i < ladder.film.size(); ++i) {
    EXPECT_LE(ladder.film[i].systematic, 2.0 * ladder.film[i].noise) << i;
    EXPECT_LE(ladder.height[i].systematic, 2.0 * ladder.height[i].noise) << i;
  }
}


}  // namespace
}  // namespace bleedsim