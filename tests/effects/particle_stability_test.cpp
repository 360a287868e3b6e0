// The particle flow's hard cases (scenarios/hard/*.toml, one test each): every case runs on the CPU
// reference through one shared checker, run_and_check(), which asserts after every frame
//   * every slot's position and velocity finite, live or not;
//   * every live particle inside the panel, min_x ≤ x ≤ max_x and min_y ≤ y ≤ max_y: nothing
//     leaves through a wall or falls through the floor;
//   * the accounting exact: emitted = alive + expired + overwritten, and alive = the number of
//     slots whose age is below the lifetime, counted from the age field;
//   * the overlap bounded: the deepest d − |xi − xj| over live pairs past their birth, found with
//     the test's own grid (measure_crowding), below half a diameter (no pair passes through
//     another), and once the particles have landed below a tenth of a diameter: the contact is made
//     stiff enough for the deepest pile's bottom contacts to overlap ⅔·compression on average, and
//     a settled pile's contact forces are spread exponentially, P(f) ∝ exp(−1.5·f/⟨f⟩) (Mueth,
//     Jaeger & Nagel 1998), so the strongest of n contacts carries about ln(n)/1.5 times the mean:
//     with the default 2 % compression, 1.33 % × ln(10⁵)/1.5 = 10 % for a full-depth pile of 10⁵
//     contacts (big-pile, with 3·10⁵, takes 1.5 %);
//   * where the case is a burst of births on top of each other, no particle faster than twice the
//     speed a lone particle reaches, g/drag: the burst eases apart rather than blasting apart;
// and over the run that the kinetic energy decays once emission stops.
//
// ParticleHardCases.BigPile is labelled "slow" (tests/CMakeLists.txt): 10⁵ particles take about
// half a minute on two cores at -O2, and the -O0 build leaves it out.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/runtime/input_error.h"
#include "core/effects/particle_accounting.h"
#include "core/effects/particle_model.h"
#include "core/io/scenario.h"
#include "core/runtime/simulation.h"
#include "tests/runtime/field_values.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

const BackendChoice kCpu{BackendChoice::Want::cpu, 2};

std::string hard_scenario(const std::string& name) {
  return (fs::path(test::source_dir()) / "scenarios" / "hard" / (name + ".toml")).string();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}


// One frame's particles as the library reports them.
struct Particles {
  std::vector<float> position;  // mm, (x, y) per slot
  std::vector<float> velocity;  // mm/s
  std::vector<std::uint32_t> age;
  ParticleCounts counts;

  explicit Particles(const Simulation& sim)
      : position(test::field_values<float>(sim, "particles/position")),
        velocity(test::field_values<float>(sim, "particles/velocity")),
        age(test::field_values<std::uint32_t>(sim, "particles/age")) {
    const std::vector<std::uint64_t> c = test::field_values<std::uint64_t>(sim, "particles/accounting");
    counts = {c.at(0), c.at(1), c.at(2), c.at(3)};
  }
  int slots() const { return int(age.size()); }
};

// Kinetic energy per unit mass of the live particles, mm²/s².
double kinetic_energy(const ParticleModel& m, const Particles& p) {
  double sum = 0.0;
  for (int s = 0; s < p.slots(); ++s) {
    if (!is_alive(m, p.age[s])) continue;
    const double vx = p.velocity[2 * s], vy = p.velocity[2 * s + 1];
    sum += 0.5 * (vx * vx + vy * vy);
  }
  return sum;
}

struct Crowding {
  double max_overlap_mm = 0.0;  // over live pairs whose particles are both at least min_age old
  int max_per_cell = 0;         // most live particles in one of the library's cells (edge cell_mm)
};

// The test's own neighbour search, independent of the library's grid, sort and max_per_cell: a
// uniform grid of one-diameter cells over the panel, a counting sort into it, and every pair in a
// cell and its four forward neighbours examined in double precision. Particles younger than
// min_age steps are left out of the overlap: a new particle is placed at its cut whatever is there
// (coincident with another, or inside a pile), so its overlap measures the emission, not the
// contact model; after min_age steps the contacts have had time to push it out.
Crowding measure_crowding(const ParticleModel& m, const Particles& p, std::uint32_t min_age) {
  const double d = m.diameter_mm;
  const double x0 = m.min_x, y0 = m.min_y;
  const int nx = int((double(m.max_x) - x0) / d) + 1, ny = int((double(m.max_y) - y0) / d) + 1;
  const auto cell_of = [&](int s) {
    const int cx = std::clamp(int(std::floor((p.position[2 * s] - x0) / d)), 0, nx - 1);
    const int cy = std::clamp(int(std::floor((p.position[2 * s + 1] - y0) / d)), 0, ny - 1);
    return cy * nx + cx;
  };
  std::vector<int> start(std::size_t(nx) * ny + 1, 0);
  std::vector<int> chosen;
  for (int s = 0; s < p.slots(); ++s)
    if (is_alive(m, p.age[s]) && p.age[s] >= min_age) chosen.push_back(s), ++start[cell_of(s) + 1];
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<int> order(chosen.size());
  std::vector<int> cursor(start.begin(), start.end() - 1);
  for (const int s : chosen) order[cursor[cell_of(s)]++] = s;

  Crowding out;
  const auto pair = [&](int a, int b) {
    const double dx = double(p.position[2 * a]) - p.position[2 * b];
    const double dy = double(p.position[2 * a + 1]) - p.position[2 * b + 1];
    const double r2 = dx * dx + dy * dy;
    if (r2 < d * d) out.max_overlap_mm = std::max(out.max_overlap_mm, d - std::sqrt(r2));
  };
  for (int cy = 0; cy < ny; ++cy)
    for (int cx = 0; cx < nx; ++cx) {
      const int c = cy * nx + cx;
      for (int k = start[c]; k < start[c + 1]; ++k) {
        // The rest of its own cell, then the cells right, below-left, below and below-right: each
        // pair of neighbouring cells once.
        for (int j = k + 1; j < start[c + 1]; ++j) pair(order[k], order[j]);
        for (const auto& [ox, oy] : {std::pair{1, 0}, std::pair{-1, 1}, std::pair{0, 1}, std::pair{1, 1}}) {
          if (cx + ox < 0 || cx + ox >= nx || cy + oy >= ny) continue;
          const int n = (cy + oy) * nx + cx + ox;
          for (int j = start[n]; j < start[n + 1]; ++j) pair(order[k], order[j]);
        }
      }
    }

  // Occupancy of the library's cells: floor(position / cell_mm), every live particle.
  std::vector<int> per_cell(std::size_t(m.cells_x) * m.cells_y, 0);
  for (int s = 0; s < p.slots(); ++s) {
    if (!is_alive(m, p.age[s])) continue;
    const int cx = std::clamp(int(std::floor(p.position[2 * s] / double(m.cell_mm))), 0, m.cells_x - 1);
    const int cy = std::clamp(int(std::floor(p.position[2 * s + 1] / double(m.cell_mm))), 0, m.cells_y - 1);
    out.max_per_cell = std::max(out.max_per_cell, ++per_cell[std::size_t(cy) * m.cells_x + cx]);
  }
  return out;
}

// The first thing wrong with one frame's particles, or "" when all holds.
std::string frame_problem(const ParticleModel& m, const Particles& p) {
  std::ostringstream why;
  int live = 0;
  for (int s = 0; s < p.slots(); ++s) {
    const float x = p.position[2 * s], y = p.position[2 * s + 1];
    const float vx = p.velocity[2 * s], vy = p.velocity[2 * s + 1];
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(vx) || !std::isfinite(vy)) {
      why << "slot " << s << " (age " << p.age[s] << ") is not finite: position (" << x << ", " << y
          << "), velocity (" << vx << ", " << vy << ")";
      return why.str();
    }
    if (!is_alive(m, p.age[s])) continue;
    ++live;
    if (!(x >= m.min_x && x <= m.max_x && y >= m.min_y && y <= m.max_y)) {
      why << "slot " << s << " at (" << x << ", " << y << ") is outside the panel [" << m.min_x << ", "
          << m.max_x << "] x [" << m.min_y << ", " << m.max_y << "]";
      return why.str();
    }
  }
  const ParticleCounts& c = p.counts;
  if (c.emitted != c.alive + c.expired + c.overwritten) {
    why << "accounting: emitted " << c.emitted << " != alive " << c.alive << " + expired " << c.expired
        << " + overwritten " << c.overwritten;
    return why.str();
  }
  if (std::uint64_t(live) != c.alive) {
    why << "accounting says " << c.alive << " alive, but " << live << " slots have an age below the lifetime";
    return why.str();
  }
  return "";
}

// No pair passes through another: its overlap stays below half a diameter, past the new particle's
// birth (until then its forces are weak by design, and coincident births overlap fully).
constexpr double kPassThrough = 0.5;
// At rest: a tenth of a diameter (the header says where the models' compression comes from).
constexpr double kAtRest = 0.10;

// What a case expects beyond the per-frame invariants.
struct Expect {
  // A burst: no particle faster than twice g/drag.
  bool burst = false;
  // The deepest overlap at rest, in diameters.
  double at_rest = kAtRest;
  // The kinetic energy at the last frame below this fraction of the energy when emission stopped.
  double end_energy_ratio = 0.01;
  // Most live particles in one of the library's cells at the last frame; 0: unchecked.
  int max_per_cell_at_end = 0;
};

struct RunSummary {
  std::int64_t frames = 0;
  std::uint64_t steps = 0;
  std::uint64_t max_alive = 0;
  ParticleCounts final_counts;
  double max_overlap_mm = 0.0;       // any frame
  std::int64_t max_overlap_frame = -1;
  double rest_overlap_mm = 0.0;      // the deepest in the last quarter after emission stopped
  double max_speed = 0.0;            // mm/s, any frame
  double energy_at_stop = 0.0;       // the first frame at or after the last cut stops bleeding
  double energy_at_end = 0.0;
  double first_quarter_max = 0.0;    // max KE over the first and last quarters of the frames
  double last_quarter_max = 0.0;     // after emission stopped
  int max_per_cell_at_end = 0;
  double seconds = 0.0;
};

// When the last cut stops bleeding particles.
double emission_end_s(const Scene& scene) {
  double end = 0.0;
  for (const Cut& cut : scene.cuts)
    if (cut.wound_mm * cut.flow_mm3_per_s_per_mm > 0.0) end = std::max(end, cut.start_s + cut.bleed_s);
  return end;
}

std::string describe(const std::string& name, const Scene& scene, const ParticleModel& m, const RunSummary& r,
                     const Expect& e) {
  const ParticleCounts& c = r.final_counts;
  const ParticleParams& pp = *scene.particles;
  const double d = m.diameter_mm;
  char text[1400];
  std::snprintf(text, sizeof text,
                "[hard/%s] %llu particles emitted, at most %llu alive; %llu steps (%lld frames), dt %.4g ms = %.3f of the "
                "limit %.4g ms\n"
                "  max overlap %.1f%% of d (frame %lld; bound %.0f%%); at rest %.1f%% (bound %.0f%%)\n"
                "  KE at emission stop %.4g, at end %.4g (ratio %.3g, bound %.3g); max KE first/last quarter after stop "
                "%.4g / %.4g\n"
                "  end: emitted %llu = alive %llu + expired %llu + overwritten %llu; max per cell %d; fastest %.3g mm/s; "
                "%.2f s",
                name.c_str(), (unsigned long long)c.emitted, (unsigned long long)r.max_alive,
                (unsigned long long)r.steps, (long long)r.frames, m.dt_s * 1e3,
                m.dt_s / particle_mechanics(pp, scene.domain, scene.frame_rate_hz).step_limit_s,
                1e3 * particle_mechanics(pp, scene.domain, scene.frame_rate_hz).step_limit_s,
                100.0 * r.max_overlap_mm / d, (long long)r.max_overlap_frame, 100.0 * kPassThrough,
                100.0 * r.rest_overlap_mm / d, 100.0 * e.at_rest,
                r.energy_at_stop, r.energy_at_end, r.energy_at_end / r.energy_at_stop, e.end_energy_ratio,
                r.first_quarter_max, r.last_quarter_max, (unsigned long long)c.emitted, (unsigned long long)c.alive,
                (unsigned long long)c.expired, (unsigned long long)c.overwritten, r.max_per_cell_at_end,
                r.max_speed, r.seconds);
  return text;
}

// Runs a scene to its end on the CPU reference, checking every frame; then the energy's decay and
// the end state's crowding. Stops at the first frame that breaks an invariant.
// `each_frame`, when given, sees every frame's particles too.
void run_and_check(const std::string& name, Scene scene, const Expect& expect, RunSummary* out,
                   const std::function<void(const Particles&)>& each_frame = nullptr) {
  const auto began = std::chrono::steady_clock::now();
  const ParticleModel m = make_particle_model(scene);
  const double stop_s = emission_end_s(scene);
  const ParticleMechanics mech = particle_mechanics(*scene.particles, scene.domain, scene.frame_rate_hz);
  const std::uint32_t settled_age = std::uint32_t(m.birth_steps) + std::uint32_t(mech.substeps);  // born, and a frame
  const double terminal_speed = std::hypot(m.gravity_x, m.gravity_y) / scene.particles->drag_per_s;
  const std::int64_t frames = scene.frame_count();
  const double frame_rate = scene.frame_rate_hz;
  // The frames from the one emission stops in: the last quarter of them is "at rest".
  const std::int64_t first_after_stop = std::int64_t(std::ceil(stop_s * frame_rate - 1e-9)) - 1;
  const std::int64_t after_stop = frames - std::max<std::int64_t>(first_after_stop, 0);
  ASSERT_GE(after_stop, 8) << name << ": too few frames after emission stops at " << stop_s << " s";
  const std::int64_t rest_from = frames - after_stop / 4;
  const Scene copy = scene;
  Simulation sim(std::move(scene), kCpu);
  RunSummary r;
  std::vector<double> energy_after_stop;  // one per frame from the one emission stopped in
  for (std::int64_t k = 0; k < frames; ++k) {
    sim.step();
    const Particles p(sim);
    const std::string problem = frame_problem(m, p);
    ASSERT_EQ(problem, "") << name << ", frame " << k << " (t = " << sim.time_s() << " s)";
    const Crowding crowd = measure_crowding(m, p, settled_age);
    if (crowd.max_overlap_mm > r.max_overlap_mm) r.max_overlap_mm = crowd.max_overlap_mm, r.max_overlap_frame = k;
    ASSERT_LT(crowd.max_overlap_mm, kPassThrough * m.diameter_mm)
        << name << ", frame " << k << " (t = " << sim.time_s() << " s): overlap of "
        << crowd.max_overlap_mm / m.diameter_mm << " diameters";
    if (k >= rest_from) {
      r.rest_overlap_mm = std::max(r.rest_overlap_mm, crowd.max_overlap_mm);
      ASSERT_LT(crowd.max_overlap_mm, expect.at_rest * m.diameter_mm)
          << name << ", frame " << k << " (t = " << sim.time_s() << " s), at rest: overlap of "
          << crowd.max_overlap_mm / m.diameter_mm << " diameters";
    }
    for (int s = 0; s < p.slots(); ++s)
      if (is_alive(m, p.age[s]))
        r.max_speed = std::max(r.max_speed, std::hypot(double(p.velocity[2 * s]), double(p.velocity[2 * s + 1])));
    if (expect.burst) {
      ASSERT_LT(r.max_speed, 2.0 * terminal_speed) << name << ", frame " << k << " (t = " << sim.time_s() << " s)";
    }
    if (each_frame) each_frame(p);
    r.max_alive = std::max(r.max_alive, p.counts.alive);
    const double ke = kinetic_energy(m, p);
    if (k >= first_after_stop) energy_after_stop.push_back(ke);
    if (k == frames - 1) {
      r.final_counts = p.counts;
      r.max_per_cell_at_end = crowd.max_per_cell;
    }
  }
  r.frames = frames;
  r.steps = std::uint64_t(frames) * std::uint64_t(mech.substeps);

  // The energy after emission stops: nothing feeds the particles but gravity, while drag and the
  // dashpots take energy out, so a stable run settles into a resting pile (or its particles
  // expire) and the kinetic energy falls towards zero; an instability feeds it instead. So: the
  // energy at the end a small fraction of the energy when emission stopped, and no late growth —
  // the most over the last quarter of the frames after the stop below the most over the first.
  const std::size_t n = energy_after_stop.size(), quarter = n / 4;
  r.energy_at_stop = energy_after_stop.front();
  r.energy_at_end = energy_after_stop.back();
  r.first_quarter_max = *std::max_element(energy_after_stop.begin(), energy_after_stop.begin() + quarter);
  r.last_quarter_max = *std::max_element(energy_after_stop.end() - quarter, energy_after_stop.end());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  *out = r;
  std::cout << describe(name, copy, m, r, expect) << std::endl;

  // Against the most there was once emission stopped (a burst still lies still when its cut stops).
  const double reference = std::max(r.energy_at_stop, r.first_quarter_max);
  EXPECT_GT(reference, 0.0) << name << ": nothing moving after emission stopped; the decay means nothing";
  EXPECT_LE(r.energy_at_end, expect.end_energy_ratio * reference) << name;
  EXPECT_LE(r.last_quarter_max, r.first_quarter_max) << name;
  if (expect.max_per_cell_at_end > 0) {
    EXPECT_LE(r.max_per_cell_at_end, expect.max_per_cell_at_end) << name;
  }
}

Scene load_hard(const std::string& name) { return load_scenario(hard_scenario(name)).scene; }

// ---- the cases ---------------------------------------------------------------------------------

// The emission per step of a cut, in particles.
double per_step(const Scene& scene, const Cut& cut) {
  return cut.wound_mm * cut.flow_mm3_per_s_per_mm / scene.particles->particle_volume_mm3 / particle_steps_per_s(scene);
}

// A burst of coincident births: they ease apart (soft births) instead of blasting apart, under
// twice the terminal speed (checked every frame by run_and_check).
TEST(ParticleHardCases, SamePoint) {
  Scene scene = load_hard("same-point");
  const ParticleParams& p = *scene.particles;
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
  const std::uint64_t capacity = std::uint64_t(scene.particles->capacity);
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
  const ParticleParams& p = *scene.particles;
  ASSERT_EQ(p.substeps, 0) << "the scene should take the fewest sub-steps";
  const ParticleMechanics mech = particle_mechanics(p, scene.domain, scene.frame_rate_hz);
  ASSERT_LT(mech.dt_s, mech.step_limit_s);
  ASSERT_GE(1.0 / (scene.frame_rate_hz * (mech.substeps - 1)), mech.step_limit_s);
  RunSummary r;
  run_and_check("stability-edge", std::move(scene), Expect{}, &r);
}

TEST(ParticleHardCases, StabilityEdgeOneSubStepFewerIsRefused) {
  Scene scene = load_hard("stability-edge");
  const int fewest = particle_mechanics(*scene.particles, scene.domain, scene.frame_rate_hz).substeps;
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
  const ParticleModel m = make_particle_model(scene);
  // The clamp did its part: particles sat exactly on the bottom-left corner point, and on the
  // right wall's line.
  int most_in_corner = 0, most_on_right_wall = 0;
  const auto count_clamped = [&](const Particles& p) {
    int in_corner = 0, on_right_wall = 0;
    for (int s = 0; s < p.slots(); ++s) {
      if (!is_alive(m, p.age[s])) continue;
      in_corner += p.position[2 * s] == m.min_x && p.position[2 * s + 1] == m.max_y;
      on_right_wall += p.position[2 * s] == m.max_x;
    }
    most_in_corner = std::max(most_in_corner, in_corner);
    most_on_right_wall = std::max(most_on_right_wall, on_right_wall);
  };
  // The corner's pile is the deepest mound the ring's particles make (a quarter-disc against two
  // walls), which is what the contact is made stiff for: the flat floor's bound holds here too.
  Expect expect;
  RunSummary r;
  run_and_check("corner-cut", std::move(scene), expect, &r, count_clamped);
  if (HasFatalFailure()) return;
  std::cout << "  most particles exactly on the bottom-left corner point " << most_in_corner
            << ", on the right wall's line " << most_on_right_wall << std::endl;
  EXPECT_GT(most_in_corner, 0);
  EXPECT_GT(most_on_right_wall, 0);
  EXPECT_EQ(r.final_counts.alive, 2000u);
}

TEST(ParticleHardCases, CrowdedCells) {
  Scene scene = load_hard("crowded-cells");
  const ParticleModel m = make_particle_model(scene);
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

// ---- the default panel comes to rest ------------------------------------------------------------

// The issue's bound: 95 % of the particles below 0.1 mm/s within 3 s of the last emission, on the
// default scenario's panel (the scene run on to that time). The grip holds what drag has slowed
// (docs/particles.md, "Coming to rest"): a particle on the mucosa stops once its share of the
// weight is under the yield, and a pool's edge is pinned. Whether one late drop is still creeping
// when the clock stops is chaos (it depends on where each particle's rounding put it), so the
// bound is on the ensemble: the particles of four seeds pooled, and each seed's share reported.
TEST(ParticleRest, TheDefaultPanelStopsWithinThreeSecondsOfTheLastEmission) {
  const Scene base = load_scenario((fs::path(test::source_dir()) / "scenarios" / "default.toml").string()).scene;
  double last_emission = 0.0;
  for (const Cut& cut : base.cuts) last_emission = std::max(last_emission, cut.start_s + cut.bleed_s);
  constexpr double kWithin = 3.0, kSlow = 0.1, kShare = 0.95;
  long pooled_alive = 0, pooled_still = 0;
  for (const std::uint64_t seed : {1, 2, 3, 4}) {
    Scene scene = base;
    scene.seed = seed;
    scene.duration_s = last_emission + kWithin;
    const ParticleModel m = make_particle_model(scene);
    Simulation sim(scene, kCpu);
    while (sim.frames_done() < scene.frame_count()) sim.step();
    const Particles p(sim);
    int alive = 0, still = 0;
    for (int s = 0; s < p.slots(); ++s) {
      if (!is_alive(m, p.age[s])) continue;
      ++alive;
      still += std::hypot(p.velocity[2 * s], p.velocity[2 * s + 1]) < kSlow;
    }
    std::cout << "seed " << seed << ": " << 100.0 * still / std::max(alive, 1) << " % of " << alive << " below "
              << kSlow << " mm/s " << kWithin << " s after the last emission at " << last_emission << " s" << std::endl;
    pooled_alive += alive;
    pooled_still += still;
  }
  EXPECT_GE(double(pooled_still) / double(pooled_alive), kShare);
}

}  // namespace
}  // namespace bleedsim
