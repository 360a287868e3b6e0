// The particle flow's hard cases (scenarios/hard/*.toml, one test each): every case runs on the CPU
// reference through one shared checker, run_and_check() (tests/effects/hard_case_check.h, which
// lists what it asserts after every frame and over the run), and adds its own expectations. The
// bleeding effects' hard cases (suction, contact, pulse, vessels) are in bleeding_hard_test.cpp.
//
// ParticleHardCases.BigPile is labelled "slow" (tests/CMakeLists.txt): 10⁵ particles take about
// half a minute on two cores at -O2, and the -O0 build leaves it out.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/io/scenario.h"
#include "core/runtime/input_error.h"
#include "core/simulation/simulation.h"
#include "tests/effects/hard_case_check.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;
using test::Expect;
using test::hard_scenario;
using test::load_hard;
using test::Particles;
using test::run_and_check;
using test::RunSummary;

const BackendChoice kCpu{BackendChoice::Want::cpu, 2};

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// ---- the cases ---------------------------------------------------------------------------------

// The emission per step of a cut, in particles.
double per_step(const Scene& scene, const Cut& cut) {
  return cut.wound_mm * cut.flow_mm3_per_s_per_mm / scene.effects.get<ParticleParams>().particle_volume_mm3 /
         resolve_particles(scene).steps_per_s;
}

// A burst of coincident births: they ease apart (soft births) instead of blasting apart, under
// twice the terminal speed (checked every frame by run_and_check).
TEST(ParticleHardCases, SamePoint) {
  Scene scene = load_hard("same-point");
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  ASSERT_EQ(p.jitter_mm, 0.0);
  ASSERT_EQ(p.velocity_jitter_mm_s, 0.0);
  ASSERT_EQ(scene.cuts.size(), 1u);
  // Several particles per step: the ones born in the same step are exactly coincident.
  ASSERT_GT(per_step(scene, scene.cuts[0]), 1.0);
  Expect expect;
  expect.burst = true;
  RunSummary r;
  run_and_check("same-point", std::move(scene), expect, &r);
  if (HasFatalFailure()) return;
  EXPECT_EQ(r.final_counts.emitted, 1200u);  // 100 mm³/s over 1 mm of wound for 48 ms, in 0.004 mm³
  EXPECT_EQ(r.final_counts.alive, 1200u);
}

TEST(ParticleHardCases, RingWrap) {
  Scene scene = load_hard("ring-wrap");
  const std::uint64_t capacity = std::uint64_t(scene.effects.get<ParticleParams>().capacity);
  RunSummary r;
  run_and_check("ring-wrap", std::move(scene), Expect{}, &r);
  if (HasFatalFailure()) return;
  const ParticleCounts& c = r.final_counts;
  EXPECT_EQ(c.emitted, 6200u);            // 1200/s for 5 s and 100/s for 2 s
  EXPECT_GE(c.emitted, 10 * capacity);    // the ring went round at least ten times ...
  EXPECT_GT(c.overwritten, 0u);           // ... taking slots from live particles,
  EXPECT_GT(c.expired, 0u);               // and some particles lived out their lifetime
  EXPECT_GT(c.alive, 0u);                 // and some still live at the end
  EXPECT_EQ(r.max_alive, capacity);
}

TEST(ParticleHardCases, BigPile) {
  Scene scene = load_hard("big-pile");
  Expect expect;
  // 10 s after the rain stops the pile is at rest: the grip holds what drag has slowed.
  expect.end_energy_ratio = 1e-4;
  expect.max_per_cell_at_end = 4;
  RunSummary r;
  run_and_check("big-pile", std::move(scene), expect, &r);
  if (HasFatalFailure()) return;
  EXPECT_EQ(r.final_counts.alive, 100000u);
}

// The fewest sub-steps the contact allows (substeps = 0) run stably to rest; one fewer is refused.
TEST(ParticleHardCases, StabilityEdge) {
  Scene scene = load_hard("stability-edge");
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  ASSERT_EQ(p.substeps, 0) << "the scene should take the fewest sub-steps";
  const ParticleMechanics mech = resolve_particles(p, scene).mechanics;
  ASSERT_LT(mech.dt_s, mech.step_limit_s);
  ASSERT_GE(1.0 / (scene.frame_rate_hz * (mech.substeps - 1)), mech.step_limit_s);
  RunSummary r;
  run_and_check("stability-edge", std::move(scene), Expect{}, &r);
}

TEST(ParticleHardCases, StabilityEdgeOneSubStepFewerIsRefused) {
  Scene scene = load_hard("stability-edge");
  const int fewest = resolve_particles(scene.effects.get<ParticleParams>(), scene).mechanics.substeps;
  const std::string text = read_text(hard_scenario("stability-edge"));
  const std::string fewer =
      std::regex_replace(text, std::regex(R"((\n)\[particles\]\n)"), "$1[particles]\nsubsteps = " + std::to_string(fewest - 1) + "\n");
  ASSERT_NE(fewer, text);
  const fs::path file =
      fs::temp_directory_path() / ("bleedsim-stability-edge-" + std::to_string(::getpid()) + ".toml");
  std::ofstream(file, std::ios::binary) << fewer;
  try {
    load_scenario(file.string());
    ADD_FAILURE() << "loaded a scene with " << fewest - 1 << " sub-steps, past the stability limit";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "particles.substeps") << e.what();
  }
  fs::remove(file);
}

TEST(ParticleHardCases, CornerCut) {
  Scene scene = load_hard("corner-cut");
  ASSERT_EQ(scene.cuts.size(), 2u);
  EXPECT_EQ(scene.cuts[0].x_mm, 0.0);
  EXPECT_EQ(scene.cuts[0].y_mm, scene.domain.height_mm);
  EXPECT_EQ(scene.cuts[1].x_mm, scene.domain.width_mm);
  EXPECT_EQ(scene.cuts[1].y_mm, 0.0);
  const ParticleModel m = resolve_particles(scene).model;
  // At rest a particle against a wall is held there by its neighbours' contacts: along the wall's
  // normal the wall's spring, k_w·δ_w, balances their pushes, k·δ·cos θ, gravity, and what the
  // grip leaves unbalanced (a sleeper wakes past 2·grip·(1 + γ·dt)). Its neighbours' centres are at
  // least 60° apart around it and on its side of the wall, so their normal components add to at
  // most √3 (at 60° and 120° from the wall; at 0° and 60° in a corner, 1.5):
  // δ_w ≤ √3·(k/k_w)·δ_max + (g + 2·grip·(1 + γ·dt))/k_w, and √3·k/k_w = 1. The corner's pile is not
  // at its design pressure (births inside the pool press it, and the grip keeps what they pressed),
  // so the bound is the pairs' own deepest overlap in the same frame, not the design compression.
  const double unbalanced_mm_s2 = std::hypot(m.gravity_x, m.gravity_y) + 2.0 * (m.yield + m.pinning) * m.drag_divisor;
  const double design = scene.effects.get<ParticleParams>().compression * m.diameter_mm;
  const double duration_s = scene.duration_s;
  const std::uint32_t settled_age = std::uint32_t(m.birth_steps);
  int most_in_corner = 0, most_on_right_wall = 0, frames_at_rest = 0;
  double deepest_at_rest = 0.0, worst_excess = -1.0;
  const auto count_pressed = [&](const Particles& p) {
    int in_corner = 0, on_right_wall = 0;
    for (int s = 0; s < p.slots(); ++s) {
      if (!is_alive(m, p.age[s])) continue;
      in_corner += p.position[2 * s] <= m.min_x && p.position[2 * s + 1] >= m.max_y;
      on_right_wall += p.position[2 * s] >= m.max_x;
    }
    most_in_corner = std::max(most_in_corner, in_corner);
    most_on_right_wall = std::max(most_on_right_wall, on_right_wall);
    if (p.t_s < duration_s - 0.5) return;
    ++frames_at_rest;
    const double into_wall = deepest_into_a_wall_mm(m, p);
    const double bound = measure_crowding(m, p, settled_age).max_overlap_mm + unbalanced_mm_s2 / m.wall_stiffness;
    deepest_at_rest = std::max(deepest_at_rest, into_wall);
    worst_excess = std::max(worst_excess, into_wall - bound);
  };
  Expect expect;
  RunSummary r;
  run_and_check("corner-cut", std::move(scene), expect, &r, count_pressed);
  if (HasFatalFailure()) return;
  std::cout << "  most particles pressed into the bottom-left corner " << most_in_corner << ", against the right wall "
            << most_on_right_wall << "; deepest into a wall over the last 0.5 s of " << duration_s << " s "
            << 100.0 * deepest_at_rest / m.diameter_mm << "% of d (the design compression " << 100.0 * design / m.diameter_mm
            << "%), past its frame's deepest pair by at most " << 100.0 * worst_excess / m.diameter_mm << "% of d"
            << std::endl;
  EXPECT_GT(most_in_corner, 0);
  EXPECT_GT(most_on_right_wall, 0);
  EXPECT_GT(frames_at_rest, 0);
  EXPECT_LE(worst_excess, 0.0);
  EXPECT_EQ(r.final_counts.alive, 2000u);
}

TEST(ParticleHardCases, CrowdedCells) {
  Scene scene = load_hard("crowded-cells");
  const ParticleModel m = resolve_particles(scene).model;
  ASSERT_EQ(scene.cuts.size(), 1u);
  const Cut& cut = scene.cuts[0];
  // Every step puts several new particles into one cell, on top of the crowd already there.
  ASSERT_GT(per_step(scene, cut), 5.0);
  const auto cell = [&](double v) { return std::floor(v / m.cell_mm); };
  ASSERT_EQ(cell(cut.x_mm - m.jitter_mm), cell(cut.x_mm + m.jitter_mm));
  ASSERT_EQ(cell(cut.y_mm - m.jitter_mm), cell(cut.y_mm + m.jitter_mm));
  // Spread out at the end: a resting hexagonal pile averages under two particles per cell of the
  // range (1.3 d) across, and five in one such cell need two of them overlapping deeply.
  Expect expect;
  expect.burst = true;
  expect.max_per_cell_at_end = 4;
  RunSummary r;
  run_and_check("crowded-cells", std::move(scene), expect, &r);
}

// ---- the default panel comes to rest, and stays at rest -----------------------------------------

// When the default panel (four seeds) first comes to rest after the last emission, the first frame at
// which no live particle moves faster than 0.1 mm/s, and the fastest any particle moves after it to
// the end of the scene. Blood that has stopped sleeps (docs/particles.md#rest) at exactly no speed,
// so after that frame nothing should move again: no late avalanche of a pile that had crept, no drop
// that restarts.
struct RestOfThePanel {
  double end_s;  // the scene's duration
  double last_emission_s;
  double stopped_s;  // −1: never
  double fastest_after_mm_s;
  double fastest_from_two_s_after_mm_s;  // from 2 s after the last emission on
};
constexpr double kSlow = 0.1;

RestOfThePanel rest_of_the_default_panel(bool film_depth, std::uint64_t seed) {
  Scene scene = load_scenario((fs::path(test::source_dir()) / "scenarios" / "default.toml").string()).scene;
  if (film_depth) {
    ParticleParams p = scene.effects.get<ParticleParams>();
    p.film_depth = true;
    p.cohesion_mm3_s2 = 0.0;
    scene.effects.set(p);
  }
  scene.seed = seed;
  RestOfThePanel r{scene.duration_s, 0.0, -1.0, 0.0, 0.0};
  for (const Cut& cut : scene.cuts) r.last_emission_s = std::max(r.last_emission_s, cut.start_s + cut.bleed_s);
  const ParticleModel m = resolve_particles(scene).model;
  Simulation sim(scene, kCpu);
  while (sim.frames_done() < scene.frame_count()) {
    sim.step();
    if (sim.time_s() < r.last_emission_s) continue;
    const Particles p(sim);
    double fastest = 0.0;
    for (int s = 0; s < p.slots(); ++s)
      if (is_alive(m, p.age[s])) fastest = std::max(fastest, p.speed(s));
    if (sim.time_s() >= r.last_emission_s + 2.0)
      r.fastest_from_two_s_after_mm_s = std::max(r.fastest_from_two_s_after_mm_s, fastest);
    if (r.stopped_s >= 0.0) r.fastest_after_mm_s = std::max(r.fastest_after_mm_s, fastest);
    else if (fastest <= kSlow) r.stopped_s = sim.time_s();
  }
  std::cout << "seed " << seed << ": still from " << r.stopped_s << " s (" << r.stopped_s - r.last_emission_s
            << " s after the last emission), then at most " << r.fastest_after_mm_s << " mm/s; from 2 s after it at most "
            << r.fastest_from_two_s_after_mm_s << " mm/s" << std::endl;
  return r;
}

// Issue 36's bound: from 2 s after the last emission to the end of the scene, at every frame, no
// live particle moves faster than 0.1 mm/s, on the default scenario over four seeds: every flow on
// the panel has stopped by then, and nothing stopped starts again. Each seed must hold it, not their
// pool.
TEST(ParticleRest, TheDefaultPanelStaysStoppedFromTwoSecondsAfterTheLastEmission) {
  for (const std::uint64_t seed : {1, 2, 3, 4})
    EXPECT_LE(rest_of_the_default_panel(false, seed).fastest_from_two_s_after_mm_s, kSlow) << "seed " << seed;
}

// The same panel with a film that has depth (docs/particles.md#a-film-with-depth): its pools stop, at
// least a second before the scene ends, and stay stopped. (Not yet within the issue's 2 s: its flows
// drain for 1.9 to 2.1 s after the last emission on these seeds, docs/particles.md#rest-of-a-film-
// with-depth; with the contact line measured at the kernel's scale, whose spurious grip inside the
// film stopped them sooner, they took 1.4 to 1.7 s.)
TEST(ParticleRest, TheDefaultPanelWithAFilmOfDepthStopsAndStaysStopped) {
  for (const std::uint64_t seed : {1, 2, 3, 4}) {
    const RestOfThePanel r = rest_of_the_default_panel(true, seed);
    ASSERT_GE(r.stopped_s, 0.0) << "seed " << seed;
    // Not physics: a second left so that "stays stopped" is watched over 30 frames at least.
    EXPECT_LE(r.stopped_s, r.end_s - 1.0) << "seed " << seed;
    EXPECT_LE(r.fastest_after_mm_s, kSlow) << "seed " << seed;
  }
}

}  // namespace
}  // namespace bleedsim