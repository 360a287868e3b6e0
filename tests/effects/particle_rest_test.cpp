// Rest (docs/particles.md#rest): blood that has stayed within rest_speed × rest_s of one spot for
// rest_s sleeps, at no speed, until a neighbour moves at twice the rest speed, a new particle
// overlaps it, the tip moves it, or the force on it passes twice its grip. Each
// test puts a lone particle (or two) where the model's closed form says what it does: a particle
// alone feels gravity g, drag γ and its grip a (yield + pinning: alone, it is all edge), and from
// rest under g > a its speed rises monotonically to the discrete terminal speed
// v_T = (g − a·(1 + γ·dt))/γ (tests/effects/particle_physics_test.cpp, FallsAsTheClosedFormSays).
// Choosing g for a stated v_T puts the particle on either side of the rest and wake thresholds.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "core/effects/particles/particle_params.h"
#include "tests/effects/particle_box.h"

namespace bleedsim {
namespace {

using test::ParticleBox;

// The gravity under which a lone particle's terminal speed is `share` of the rest speed.
float gravity_for(const ParticleBox& box, const ParticleParams& p, double share) {
  const ParticleModel& m = box.model();
  return float((m.yield + m.pinning) * (1.0 + p.drag_per_s * m.dt_s) + p.drag_per_s * share * p.rest_speed_mm_s);
}

bool asleep_now(const ParticleBox& box, int i) { return asleep(box.model(), box.arrays().rest[i]); }

std::vector<float> positions(const ParticleBox& box) {
  return {box.arrays().position, box.arrays().position + 2 * box.size()};
}

// At half the rest speed a particle moves less than rest_speed × rest_s in any rest_steps steps, so
// it sleeps the step its count reaches rest_steps: one step to leave the anchor it was placed with
// (the origin), then rest_steps at rest. Asleep, with no neighbour, the force on it is its grip as
// the step takes it, a·(1 + γ·dt), and γ·v_T = γ·rest_speed/2 more: under twice the grip, it stays,
// and not a bit of it moves.
TEST(ParticleRest, CreepSlowerThanTheRestSpeedSleepsOnTimeAndStays) {
  const ParticleParams p;
  ParticleBox box(test::box_scene(4, 24, p), {{2.0, 5.0}});
  box.set_gravity(0.0f, gravity_for(box, p, 0.5));
  const std::uint32_t rest_steps = box.model().rest_steps;
  ASSERT_GT(rest_steps, 100u);
  for (std::uint32_t n = 1; n <= rest_steps; ++n) {
    box.step();
    ASSERT_FALSE(asleep_now(box, 0)) << "step " << n;
    ASSERT_GT(box.speed(0), 0.0) << "step " << n;
  }
  box.step();
  ASSERT_TRUE(asleep_now(box, 0));
  EXPECT_EQ(box.speed(0), 0.0);
  const std::vector<float> slept = positions(box);
  box.run_for(1.0);
  EXPECT_TRUE(asleep_now(box, 0));
  EXPECT_EQ(box.speed(0), 0.0);
  EXPECT_EQ(positions(box), slept);
}

// At 1.5 × the rest speed, once past it (within a few 1/γ), every rest_s takes it further than
// rest_speed × rest_s: it never sleeps, and slides at its terminal speed.
TEST(ParticleRest, CreepFasterThanTheRestSpeedNeverSleeps) {
  const ParticleParams p;
  ParticleBox box(test::box_scene(4, 24, p), {{2.0, 5.0}});
  box.set_gravity(0.0f, gravity_for(box, p, 1.5));
  const long steps = std::lround(2.0 / box.dt());
  for (long n = 1; n <= steps; ++n) {
    box.step();
    ASSERT_FALSE(asleep_now(box, 0)) << "step " << n;
  }
  // Terminal within float rounding after 200 time constants 1/γ.
  EXPECT_NEAR(box.speed(0), 1.5 * p.rest_speed_mm_s, 1e-4 * p.rest_speed_mm_s);
}

// Asleep, the panel tilts: gravity at 1.99 × the grip as the step takes it leaves it asleep, at
// 2.01 × it wakes it the next step, and it slides.
TEST(ParticleRest, ASleeperWakesWhenTheForceOnItPassesTwiceItsGrip) {
  const ParticleParams p;
  ParticleBox box(test::box_scene(4, 24, p), {{2.0, 5.0}});
  box.set_gravity(0.0f, gravity_for(box, p, 0.5));
  box.run_for(0.5);
  ASSERT_TRUE(asleep_now(box, 0));
  const ParticleModel& m = box.model();
  const float held = (m.yield + m.pinning) * m.drag_divisor;
  box.set_gravity(0.0f, 1.99f * held);
  box.run_for(0.1);
  ASSERT_TRUE(asleep_now(box, 0));
  box.set_gravity(0.0f, 2.01f * held);
  box.step();
  EXPECT_FALSE(asleep_now(box, 0));
  EXPECT_GT(box.velocity(0).y, 0.0f);
  box.run_for(1.0);
  EXPECT_FALSE(asleep_now(box, 0));
}

// Two particles the grip holds (alone, a particle's grip is about twice gravity): both sleep. One
// is woken by hand and thrown at the other at 30 mm/s; the contact's push, far past the grip, wakes
// the other, which moves. A sleeper is not a wall.
TEST(ParticleRest, ANeighbourThatHitsASleeperWakesIt) {
  const ParticleParams p;
  const double d = p.diameter_mm;
  ParticleBox box(test::box_scene(4, 24, p), {{2.0, 5.0}, {2.0, 5.0 - d - 0.02}});
  box.run_for(0.5);
  ASSERT_TRUE(asleep_now(box, 0));
  ASSERT_TRUE(asleep_now(box, 1));
  const float before = box.position(0).y;
  box.arrays().rest[1] = 0;
  box.arrays().velocity[3] = 30.0f;
  bool woke = false;
  for (int n = 0; n < 200 && !woke; ++n) {
    box.step();
    woke = !asleep_now(box, 0);
  }
  ASSERT_TRUE(woke);
  box.run_for(0.05);
  EXPECT_GT(box.position(0).y, before);
}

}  // namespace
}  // namespace bleedsim
