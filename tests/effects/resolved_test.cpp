// What a scene resolves to (core/effects/resolved.h): each declared effect's settings, once, for
// every consumer to read. Checked against their definitions (docs/particles.md, docs/bleeding.md):
// the steps a second are the frame rate times the sub-steps; the suction's quota a sub-step is its
// flow over the steps a second and a particle's volume; the tip's body is its radius and a
// particle's; the splat spreads over its radius, or the diameter; nothing for what a scene lacks.
#include <gtest/gtest.h>

#include "core/effects/contact/contact_hook.h"
#include "core/effects/contact/contact_params.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/resolved.h"
#include "core/effects/suction/suction_hook.h"
#include "core/effects/suction/suction_params.h"
#include "core/simulation/simulation.h"
#include "tests/effects/bleeding_scenes.h"

namespace bleedsim {
namespace {

Scene instrument_scene() {
  Scene scene = test::bleeding_scene("resolved", Domain{32, 24, 8.0, 6.0}, 0.2);
  test::add_cut(scene, 4.0, 2.0, 0.0, 2.0, 1.0);
  scene.effects.set(SuctionParams{1.2, 3.0, 0x2});
  scene.effects.set(ContactParams{0.5});
  scene.tips = {TipPoint{0.0, 4.0, 3.0}, TipPoint{0.2, 5.0, 3.0}};
  return scene;
}

TEST(Resolved, EachDeclaredEffectsSettingsFromTheirDefinitions) {
  const Scene scene = instrument_scene();
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  const Resolved resolved = resolve(scene);
  const ParticleSettings& particles = resolved.get<ParticleSettings>();
  EXPECT_GT(particles.mechanics.substeps, 0);
  EXPECT_EQ(particles.steps_per_s, scene.frame_rate_hz * particles.mechanics.substeps);
  EXPECT_EQ(particles.model.dt_s, float(1.0 / particles.steps_per_s));
  EXPECT_EQ(particles.splat.radius_mm, float(p.diameter_mm));  // splat_radius_mm = 0: the diameter
  EXPECT_EQ(resolved.get<SuctionSettings>().particles_per_step,
            3.0 / particles.steps_per_s / p.particle_volume_mm3);
  EXPECT_EQ(resolved.get<ContactSettings>().body_mm, 0.5 + p.diameter_mm / 2.0);
}

TEST(Resolved, NothingForWhatTheSceneDoesNotDeclare) {
  Scene scene = instrument_scene();
  scene.effects.drop<SuctionParams>();
  const Resolved without_suction = resolve(scene);
  EXPECT_FALSE(without_suction.has<SuctionSettings>());
  EXPECT_TRUE(without_suction.has<ContactSettings>());
  Scene bare = test::bleeding_scene("bare", Domain{32, 24, 8.0, 6.0}, 0.2);
  bare.effects.drop<ParticleParams>();
  EXPECT_FALSE(resolve(bare).has<ParticleSettings>());
}

TEST(Resolved, TheSplatSpreadsOverItsOwnRadiusWhenGiven) {
  Scene scene = test::bleeding_scene("splat", Domain{32, 24, 8.0, 6.0}, 0.2);
  scene.effects.get<ParticleParams>().splat_radius_mm = 0.35;
  EXPECT_EQ(resolve(scene).get<ParticleSettings>().splat.radius_mm, 0.35f);
}

TEST(Resolved, TheSimulationResolvesItsSceneOnce) {
  const Simulation sim(instrument_scene(), BackendChoice{BackendChoice::Want::cpu, 1});
  const Resolved again = resolve(sim.scene());
  EXPECT_EQ(sim.resolved().get<ParticleSettings>().steps_per_s, again.get<ParticleSettings>().steps_per_s);
  EXPECT_EQ(sim.resolved().get<SuctionSettings>().particles_per_step,
            again.get<SuctionSettings>().particles_per_step);
}

}  // namespace
}  // namespace bleedsim