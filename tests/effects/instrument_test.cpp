// The instrument in the blood (docs/bleeding.md, "Suction" and "Contact"): the accounting stays
// exact with the suction taking particles; a pool within reach drains at the stated flow (the
// closed form floor(k · flow · dt / V)); suction faster than the bleeding keeps the field empty; a
// tip in a corner takes only what it reaches, one off the panel nothing; no particle is inside the
// tip's body after a sub-step, and its wake closes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/effects/contact/contact_params.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/suction/suction_params.h"
#include "core/io/scenario.h"
#include "core/physics/instrument.h"
#include "core/simulation/simulation.h"
#include "tests/effects/bleeding_scenes.h"
#include "tests/runtime/field_values.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

const BackendChoice kCpu{BackendChoice::Want::cpu, 2};

// An 8 × 6 mm panel of 0.1 mm pixels. One wound at (x, y) bleeds `blood_mm3` over its first
// 0.5 s; particles live 30 s (none expires here), the pile is shallow (few sub-steps).
Scene pool_scene(double x_mm, double y_mm, double blood_mm3, double duration_s) {
  Scene scene = test::bleeding_scene("instrument", Domain{80, 60, 8.0, 6.0}, duration_s);
  test::add_cut(scene, x_mm, y_mm, 0.0, blood_mm3 / 0.5, 0.5);
  return scene;
}

// A scripted tip from (x0, y0) at t0 to (x1, y1) at t1.
void add_path(Scene& scene, double t0, double x0, double y0, double t1, double x1, double y1) {
  scene.tips = {TipPoint{t0, x0, y0}, TipPoint{t1, x1, y1}};
}

// The particles alive in the ring, counted from their ages alone.
std::uint64_t alive_in_ring(const Simulation& sim) {
  const ParticleLifetime lifetime = resolve_particles(sim.scene()).lifetime;
  std::uint64_t alive = 0;
  for (const std::uint32_t age : test::field_values<std::uint32_t>(sim, "particles/age")) alive += is_alive(lifetime, age);
  return alive;
}

// A ring too small for the bleeding, and a short lifetime: particles expire, are overwritten and are
// aspirated, some aspirated ones then expiring or being overwritten in their turn. After every frame
// the counts add up, and the alive count is the ring's own (from the ages alone): what the
// suction took is neither counted twice nor lost, however it later leaves the ring's id range.
class SuctionAccounting : public testing::TestWithParam<BackendChoice::Want> {};

TEST_P(SuctionAccounting, IsExactEveryFrame) {
  std::string why;
  if (GetParam() == BackendChoice::Want::cuda && !cuda_device_available(&why)) GTEST_SKIP() << "no CUDA device: " << why;
  Scene scene = pool_scene(4.0, 2.0, 1.0, 2.0);
  scene.effects.get<ParticleParams>().capacity = 160;
  scene.effects.get<ParticleParams>().lifetime_s = 0.4;
  scene.effects.get<ParticleParams>().fade_s = 0.1;
  scene.cuts[0].bleed_s = 1.5;  // 2 mm³/s: 500 particles a second, 200 a lifetime, for 160 slots
  scene.effects.set(SuctionParams{0.6, 0.4, 0x2});  // 100 particles a second at most
  add_path(scene, 0.2, 4.0, 2.2, 1.8, 4.0, 2.2);
  Simulation sim(scene, BackendChoice{GetParam(), 2});
  ParticleCounts c{};
  while (sim.frames_done() < scene.frame_count()) {
    sim.step();
    c = test::particle_counts(sim);
    ASSERT_EQ(c.emitted, c.alive + c.expired + c.overwritten + c.aspirated) << "frame " << sim.frames_done();
    ASSERT_EQ(c.alive, alive_in_ring(sim)) << "frame " << sim.frames_done();
  }
  EXPECT_GT(c.expired, 0u);
  EXPECT_GT(c.overwritten, 0u);
  EXPECT_GT(c.aspirated, 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, SuctionAccounting,
                         testing::Values(BackendChoice::Want::cpu, BackendChoice::Want::cuda),
                         [](const testing::TestParamInfo<BackendChoice::Want>& info) {
                           return info.param == BackendChoice::Want::cpu ? "cpu" : "cuda";
                         });

// A pool of N₀ = 250 particles (1 mm³) lies at the bottom; from t_on = 1 s a tip whose reach covers
// the whole panel sucks at R = 0.5 mm³/s. After k sub-steps with it on it may have taken
// ⌊k · R·dt/V⌋ particles, and every particle is within reach, so it has taken min(N₀, ⌊k·x⌋),
// x = R·dt/V. At a frame's end t, k·dt lies in (t − t_on − dt, t − t_on], so the count is within
// 1 + x of the closed form min(N₀, R·(t − t_on)/V): it drains linearly, 125 particles a second,
// and is empty from t_on + 2 s on.
TEST(Suction, DrainsAPoolWithinReachAtItsFlow) {
  Scene scene = pool_scene(4.0, 1.0, 1.0, 3.5);
  scene.effects.set(SuctionParams{20.0, 0.5, 0x2});
  const double t_on = 1.0 + 1.0 / 3000.0;  // between sub-steps
  add_path(scene, t_on, 4.0, 5.5, 3.5, 4.0, 5.5);
  Simulation sim(scene, kCpu);
  const double volume = scene.effects.get<ParticleParams>().particle_volume_mm3;
  const double x = 0.5 / resolve_particles(scene).steps_per_s / volume;
  double n0 = 0;
  while (sim.frames_done() < scene.frame_count()) {
    sim.step();
    const ParticleCounts c = test::particle_counts(sim);
    const double t = sim.time_s();
    if (t < t_on) {
      EXPECT_EQ(c.aspirated, 0u) << "t = " << t;
      n0 = double(c.emitted);
      continue;
    }
    ASSERT_EQ(n0, 250.0);
    const double closed_form = std::min(n0, 0.5 * (t - t_on) / volume);
    EXPECT_NEAR(double(c.aspirated), closed_form, 1.0 + x) << "t = " << t;
    EXPECT_EQ(c.alive, std::uint64_t(n0) - c.aspirated);
  }
  EXPECT_EQ(test::particle_counts(sim).alive, 0u);
}

// A wound bleeds Q = 0.5 mm³/s for 2 s under a tip that sucks R = 1 mm³/s within 1 mm of it. Each
// step the tip takes min(alive, q_k) (everything emitted stays within its reach: the jitter is
// 0.05 mm and a particle waits at most ⌈V/(R·dt)⌉ steps), so the alive count is a queue:
// alive_k = max over j ≤ k of (E_k − E_j) − (A_k − A_j), with E and A the cumulative emission and
// quota, each a floor of a linear function: E_k − E_j ≤ Q·(t_k − t_j)/V + 1 and
// A_k − A_j ≥ R·(t_k − t_j)/V − 1. With R > Q, at most 2 particles are ever alive.
TEST(Suction, FasterThanTheBleedingKeepsTheFieldEmpty) {
  Scene scene = pool_scene(4.0, 3.0, 0.25, 3.0);
  scene.cuts[0].bleed_s = 2.0;
  scene.cuts[0].flow_mm3_per_s_per_mm = 0.5;
  scene.effects.set(SuctionParams{1.0, 1.0, 0x2});
  add_path(scene, 0.0, 4.0, 3.0, 3.0, 4.0, 3.0);
  Simulation sim(scene, kCpu);
  while (sim.frames_done() < scene.frame_count()) {
    sim.step();
    EXPECT_LE(test::particle_counts(sim).alive, 2u) << "t = " << sim.time_s();
  }
  EXPECT_EQ(test::particle_counts(sim).emitted, 250u);
}

// A tip held in the bottom-left corner, its reach 1.5 mm: it takes the blood there and nothing
// else (its reach's part on the panel); when done, no live particle is within its reach, and every
// one it left lies outside it. A tip off the panel, its reach missing it, takes nothing: the
// particles move exactly as without suction.
TEST(Suction, ATipInACornerTakesWhatItReachesAndOneOffThePanelNothing) {
  Scene corner = pool_scene(1.0, 3.0, 1.0, 3.0);
  corner.effects.set(SuctionParams{1.5, 5.0, 0x2});
  add_path(corner, 1.0, 0.0, 6.0, 3.0, 0.0, 6.0);
  Simulation sim(corner, kCpu);
  while (sim.frames_done() < corner.frame_count()) sim.step();
  const ParticleCounts c = test::particle_counts(sim);
  EXPECT_GT(c.aspirated, 0u);
  EXPECT_GT(c.alive, 0u);
  const std::vector<float> position = test::field_values<float>(sim, "particles/position");
  const std::vector<std::uint32_t> age = test::field_values<std::uint32_t>(sim, "particles/age");
  const ParticleLifetime lifetime = resolve_particles(corner).lifetime;
  for (std::size_t s = 0; s < age.size(); ++s) {
    if (!is_alive(lifetime, age[s])) continue;
    EXPECT_GT(std::hypot(position[2 * s] - 0.0, position[2 * s + 1] - 6.0), 1.5) << "slot " << s;
  }

  Scene off = pool_scene(1.0, 3.0, 1.0, 3.0), without = off;
  off.effects.set(SuctionParams{1.5, 5.0, 0x2});
  add_path(off, 0.5, -2.0, 3.0, 3.0, -1.6, 5.0);
  Simulation a(off, kCpu), b(without, kCpu);
  while (a.frames_done() < off.frame_count()) {
    a.step();
    b.step();
  }
  EXPECT_EQ(test::particle_counts(a).aspirated, 0u);
  EXPECT_EQ(a.copy_field("particles/position"), b.copy_field("particles/position"));
  EXPECT_EQ(a.copy_field("splat/thickness"), b.copy_field("splat/thickness"));
}

// Where a particle pushed out of the tip lands: outside the disc (by the test that found it in),
// inside the panel's box, and no farther than any free point of the box near the disc (points
// sampled on the circle and along the box's edges, 0.05 % of the circle apart): the nearest free
// point, up to the sampling's spacing. Points inside the disc are drawn everywhere in it, with the
// disc in the middle of the box, against a wall, and in a corner.
TEST(Contact, APushedOutParticleLandsAtTheNearestFreePoint) {
  const float x0 = 0.1f, x1 = 7.9f, y0 = 0.1f, y1 = 5.9f, r = 0.7f;
  std::mt19937 draw(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (const auto& [cx, cy] : std::vector<std::pair<float, float>>{{4.0f, 3.0f}, {0.3f, 3.0f}, {7.5f, 5.8f}, {0.1f, 0.1f}}) {
    // The free boundary near the disc, sampled.
    std::vector<Spot> free;
    for (int k = 0; k < 2000; ++k) {
      const double a = 2.0 * 3.14159265358979323846 * k / 2000.0;
      free.push_back({float(cx + (r + 1e-5) * std::cos(a)), float(cy + (r + 1e-5) * std::sin(a))});
    }
    for (float s = 0.0f; s <= 1.0f; s += 1.0f / 4096.0f)
      for (const Spot e : {Spot{x0, y0 + s * (y1 - y0)}, Spot{x1, y0 + s * (y1 - y0)}, Spot{x0 + s * (x1 - x0), y0},
                           Spot{x0 + s * (x1 - x0), y1}})
        free.push_back(e);
    for (int n = 0; n < 2000; ++n) {
      const float px = fminf(fmaxf(cx + r * unit(draw), x0), x1), py = fminf(fmaxf(cy + r * unit(draw), y0), y1);
      if (outside_disc(px, py, cx, cy, r)) continue;
      const Spot to = nearest_outside_disc(px, py, cx, cy, r, x0, x1, y0, y1);
      ASSERT_TRUE(outside_disc(to.x, to.y, cx, cy, r)) << px << ", " << py;
      ASSERT_TRUE(to.x >= x0 && to.x <= x1 && to.y >= y0 && to.y <= y1);
      double nearest = 1e9;
      for (const Spot f : free)
        if (f.x >= x0 && f.x <= x1 && f.y >= y0 && f.y <= y1 && outside_disc(f.x, f.y, cx, cy, r))
          nearest = std::min(nearest, std::hypot(double(f.x) - px, double(f.y) - py));
      EXPECT_LE(std::hypot(double(to.x) - px, double(to.y) - py), nearest + 2e-3) << px << ", " << py;
    }
  }
}

// Whether every live particle's centre is outside the tip's body, by the kernel's own float test.
testing::AssertionResult no_particle_inside(const Simulation& sim, const ToolSample& tip, float body) {
  const ParticleLifetime lifetime = resolve_particles(sim.scene()).lifetime;
  const std::vector<float> position = test::field_values<float>(sim, "particles/position");
  const std::vector<std::uint32_t> age = test::field_values<std::uint32_t>(sim, "particles/age");
  for (std::size_t s = 0; s < age.size(); ++s)
    if (is_alive(lifetime, age[s]) &&
        !outside_disc(position[2 * s], position[2 * s + 1], float(tip.x_mm), float(tip.y_mm), body))
      return testing::AssertionFailure() << "slot " << s << " at (" << position[2 * s] << ", " << position[2 * s + 1]
                                         << ") is inside the tip at (" << tip.x_mm << ", " << tip.y_mm << ")";
  return testing::AssertionSuccess();
}

// The tip's place at a frame's end, as the instrument computes it.
ToolSample tip_at_frame_end(const Simulation& sim) {
  return *tool_at(scripted_tool(sim.scene().tips), sim.time_s(), false);
}

// A tip drawn through a settled pool and back: after every frame (the last sub-step of each), no
// live particle's centre is inside its body, by the kernel's own test in float.
TEST(Contact, NoParticleIsInsideTheTipAfterASubStep) {
  Scene scene = pool_scene(4.0, 1.0, 2.0, 3.0);
  scene.effects.set(ContactParams{0.5});
  scene.tips = {TipPoint{1.0, 0.5, 5.6}, TipPoint{2.0, 7.5, 5.6}, TipPoint{3.0, 0.2, 5.9}};
  Simulation sim(scene, kCpu);
  const float body = float(0.5 + scene.effects.get<ParticleParams>().diameter_mm / 2.0);
  int checked = 0;
  while (sim.frames_done() < scene.frame_count()) {
    sim.step();
    if (sim.time_s() < 1.0) continue;
    const ToolSample tip = tip_at_frame_end(sim);
    ASSERT_TRUE(no_particle_inside(sim, tip, body)) << "t = " << sim.time_s();
    ++checked;
  }
  EXPECT_GE(checked, 59);
}

// The share of the pixels of [i0, i1) × [j0, j1) that blood covers.
double covered(const Simulation& sim, int i0, int i1, int j0, int j1) {
  const std::vector<float> film = test::field_values<float>(sim, "splat/thickness");
  int wet = 0;
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i) wet += film[std::size_t(j) * 80 + i] > 0.0f;
  return double(wet) / double((i1 - i0) * (j1 - j0));
}

// A pool 4 mm deep (4 mm³ of blood at the bottom of the 8 mm panel) and a tip (1.2 mm across with a
// particle's radius each side) drawn through it 1.5 mm below its surface at 7 mm/s. A box of
// 1 × 0.8 mm on its path is wet before the tip comes, mostly dry while the tip is over it, and wet
// again, every pixel, from 0.5 s after it has left it (at 2.87 s): the wake closes. (The 0.5 s and
// the "mostly dry" share are margins over what runs show, about 0.2 s and a third wet: tripwires on
// how fast and how wide, not derived; that it closes is the physics.) Why it must: the
// ~15 layers of blood above the wake weigh on its upper edge with about 15 g, far beyond the grip that holds a
// film's edge (pinning and yield, about 1.9 g here, docs/particles.md), so the blood runs in. No
// blood is lost: contact only moves particles. Over four seeds.
TEST(Contact, ItsWakeThroughAPoolClosesAgain) {
  for (const std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    Scene scene = pool_scene(4.0, 5.0, 4.0, 4.5);
    scene.seed = seed;
    scene.effects.set(ContactParams{0.5});
    scene.tips = {TipPoint{2.5, 0.5, 4.5}, TipPoint{3.5, 7.5, 4.5}};
    Simulation sim(scene, kCpu);
    double least_while_over = 1.0;
    std::uint64_t alive_before = 0;
    while (sim.frames_done() < scene.frame_count()) {
      sim.step();
      const double t = sim.time_s(), wet = covered(sim, 15, 25, 41, 49);
      if (t > 2.3 && t < 2.5) {
        EXPECT_EQ(wet, 1.0) << "seed " << seed << ", t = " << t << ": the box is in the pool";
        alive_before = test::particle_counts(sim).alive;
      }
      if (t > 2.65 && t < 2.8) least_while_over = std::min(least_while_over, wet);
      if (t > 3.37) {
        EXPECT_EQ(wet, 1.0) << "seed " << seed << ", t = " << t << ": the wake has closed";
      }
    }
    EXPECT_LT(least_while_over, 0.5) << "seed " << seed << ": the tip parts the pool where it is";
    EXPECT_EQ(test::particle_counts(sim).alive, alive_before) << "seed " << seed;
  }
}

// The stylus as the instrument (scenarios/falcon-suction.toml: a cut stroke with the first button,
// then a pass along the bottom with the second). The suction takes nothing until a tick has found
// the tip in contact with a suction button held, takes nothing in a frame unless such a tick is
// in it or the tip stays so from the frame before, and has taken blood by the end.
TEST(Suction, TheStylusSucksOnlyInContactWithItsButtonHeld) {
  const Scenario scenario = load_scenario(test::source_dir() + "/scenarios/falcon-suction.toml");
  Simulation sim(scenario.scene, kCpu);
  bool on = false;  // the last tick's suction: it holds until the next
  std::uint64_t before = 0;
  while (sim.frames_done() < scenario.scene.frame_count()) {
    bool on_in_frame = on;
    sim.step();
    for (const HapticTick& tick : sim.haptic_ticks()) {
      on = tick.contact && (tick.buttons & 0x2) != 0;
      on_in_frame = on_in_frame || on;
    }
    const std::uint64_t taken = test::particle_counts(sim).aspirated;
    if (!on_in_frame) {
      EXPECT_EQ(taken, before) << "t = " << sim.time_s() << ": no tick sucked";
    }
    before = taken;
  }
  EXPECT_GT(before, 100u);
}

// A host drives its stylus itself: its samples move the instrument as a trace's ticks do, and a
// scene whose stylus is its trace's, or that has none, refuses them.
TEST(Contact, AHostsStylusSamplesMoveTheInstrument) {
  Scene scene = pool_scene(4.0, 5.0, 2.0, 1.5);
  scene.haptics = HapticParams{};
  scene.effects.set(ContactParams{0.5});
  Simulation sim(scene, kCpu);
  const float body = float(0.5 + scene.effects.get<ParticleParams>().diameter_mm / 2.0);
  // The tip sweeps the pool from left to right at 8 mm/s from 0.6 s, a sample each millisecond.
  std::vector<ToolSample> samples;
  for (int n = 0; n <= 1500; ++n) {
    const double t = n / 1000.0;
    samples.push_back({t, 0.5 + 8.0 * std::max(0.0, t - 0.6), 5.5, t >= 0.6, 0});
  }
  std::size_t given = 0;
  for (int k = 0; k < scene.frame_count(); ++k) {
    const double end = scene.frame_time_s(k);
    for (; given < samples.size() && samples[given].t_s <= end; ++given) sim.add_stylus_sample(samples[given]);
    sim.step();
    if (sim.time_s() < 0.7) continue;
    // Where the instrument is: on what the host has given, which ends before the frame's end.
    const ToolSample tip = *tool_at({samples.begin(), samples.begin() + std::ptrdiff_t(given)}, end, true);
    ASSERT_TRUE(no_particle_inside(sim, tip, body)) << "t = " << sim.time_s();
  }
  EXPECT_THROW(sim.add_stylus_sample({0.0, 1.0, 1.0, true, 0}), std::invalid_argument);  // not later
  Simulation without(pool_scene(4.0, 5.0, 2.0, 1.0), kCpu);
  EXPECT_THROW(without.add_stylus_sample({0.0, 1.0, 1.0, true, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace bleedsim