// The study's knobs (core/study/study_knobs.cpp): each changes the one thing it names and holds the
// rest, a contact the time step cannot hold is refused rather than softened, refinements continue
// a ladder, and a solver's iteration count is answered with why the model has none.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "core/effects/blur/blur_params.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/vessels/vessel_params.h"
#include "core/simulation/scene_check.h"
#include "core/study/study_knobs.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

// The spread, the particles (their defaults: sub-steps and pile depth left to the model) and the blur.
Scene full_scene() {
  Scene scene = test::scene_in_code(true);
  scene.effects.set(ParticleParams{});
  scene.effects.set(BlurParams{});
  return scene;
}

// What a knob may mean, each a number a scene has.
std::map<std::string, double> meanings(const Scene& s) {
  const ParticleParams& p = s.effects.get<ParticleParams>();
  const ParticleMechanics m = resolve_particles(p, s).mechanics;
  const BlurParams& b = s.effects.get<BlurParams>();
  return {{"time step", m.dt_s},
          {"compression", p.compression},
          {"pile depth", m.depth_mm},
          {"particle diameter", p.diameter_mm},
          {"blood flow", p.flow_mm3_per_s_per_mm},
          {"film thickness", m.film_mm},
          {"surface tension", p.cohesion_mm3_s2},
          {"grip", p.pinning_mm3_s2 + p.yield_mm2_s2},
          {"largest drop held", resolve_particles(p, s).drop.radius_mm},
          {"blur width on the panel", b.sigma_px * b.downsample * s.domain.width_mm / s.domain.width_px},
          {"blur taps per sigma", b.radius_px / b.sigma_px},
          {"blur downsampling", b.downsample},
          {"pixels", double(s.domain.width_px) * s.domain.height_px},
          {"panel", s.domain.width_mm * s.domain.height_mm}};
}

TEST(StudyKnobs, EachChangesOnlyWhatItSays) {
  // Each knob at a value the base contact can run at; relative changes under 1e-12 are rounding
  // (the film's t = V/(√3/2·d²) with V·f² and d·f, the critical drop through it).
  const Scene base = full_scene();
  const struct {
    const char* knob;
    double value;
    std::set<std::string> changes;
  } cases[] = {{"compression", 0.04, {"compression"}},
               {"substeps", 2.0 * fewest_stable_substeps(base), {"time step"}},
               {"particle_size", 2.0, {"particle diameter"}},
               {"blur_radius", 2.0, {"blur taps per sigma"}},
               {"blur_downsample", 1.0, {"blur downsampling"}},
               {"resolution", 0.5, {"pixels"}}};
  const std::map<std::string, double> before = meanings(base);
  for (const auto& c : cases) {
    Scene s = base;
    find_knob(c.knob)->apply(s, c.value);
    EXPECT_FALSE(scene_problem(s)) << c.knob << ": " << scene_problem(s).text();
    std::set<std::string> changed;
    for (const auto& [name, value] : meanings(s))
      if (std::abs(value - before.at(name)) > 1e-12 * std::abs(before.at(name))) changed.insert(name);
    EXPECT_EQ(changed, c.changes) << c.knob;
  }
}

TEST(StudyKnobs, AContactTooStiffForTheTimeStepIsRefusedNotSoftened) {
  // A quarter of the compression is four times the stiffness: the base's fewest sub-steps no longer
  // hold it, and the scene is refused at particles.substeps with the step it has kept.
  Scene s = full_scene();
  const double dt = resolve_particles(s).mechanics.dt_s;
  find_knob("compression")->apply(s, s.effects.get<ParticleParams>().compression / 4);
  EXPECT_EQ(resolve_particles(s).mechanics.dt_s, dt);
  const ParamProblem problem = scene_problem(s);
  EXPECT_NE(problem.text().find("particles.substeps: a sub-step of "), std::string::npos) << problem.text();
  // Particles half the size: four times the stiffness at the same compression, refused alike.
  Scene small = full_scene();
  find_knob("particle_size")->apply(small, 0.5);
  EXPECT_NE(scene_problem(small).text().find("past the contact's stability limit"), std::string::npos);
}

// Issue 36's ladder draws every size with the same footprint: a splat radius the scene gives stays
// in mm along particle_size; one left at 0 (the diameter) follows the particles.
TEST(StudyKnobs, ParticleSizeKeepsTheSplatRadiusTheSceneGives) {
  Scene given = full_scene();
  given.effects.get<ParticleParams>().splat_radius_mm = 0.4;
  find_knob("particle_size")->apply(given, 0.25);
  EXPECT_FLOAT_EQ(resolve_particles(given).splat.radius_mm, 0.4f);
  Scene left = full_scene();
  find_knob("particle_size")->apply(left, 0.25);
  EXPECT_FLOAT_EQ(resolve_particles(left).splat.radius_mm, float(0.25 * ParticleParams{}.diameter_mm));
}

TEST(StudyKnobs, ResolutionResamplesAVesselMapReadFromAFile) {
  // By area means: a constant map stays that constant. (The procedural tissue and vessels are drawn
  // again from the scene's own seed: StudySeeds.MoveThePhysicsAndLeaveTheTissueAlone.)
  Scene png = full_scene();
  png.effects.set(VesselParams{"map.png"});
  png.vessel_density.assign(64 * 48, 0.375f);
  find_knob("resolution")->apply(png, 0.25);
  EXPECT_EQ(png.vessel_density, std::vector<float>(16 * 12, 0.375f));
}

TEST(StudyKnobs, RefinementsContinueTheLadder) {
  const auto finer = [](const char* knob, std::vector<double> levels) {
    return refined_value(*find_knob(knob), levels);
  };
  EXPECT_DOUBLE_EQ(*finer("compression", {0.08, 0.04, 0.02}), 0.01);
  EXPECT_DOUBLE_EQ(*finer("particle_size", {2, 1.4}), 0.98);  // the last ratio, 0.7, again
  EXPECT_EQ(*finer("substeps", {300, 600}), 1200);
  EXPECT_EQ(*finer("substeps", {600}), 1200);                 // one level: twice as fine
  EXPECT_EQ(*finer("blur_radius", {3, 4}), 5);                // 16/3, rounded
  EXPECT_EQ(*finer("resolution", {0.25, 0.5, 1}), 2);
  EXPECT_EQ(*finer("blur_downsample", {4, 2}), 1);
  EXPECT_FALSE(finer("blur_downsample", {2, 1}));             // ½ rounds back to 1; 0 is not a level
  EXPECT_FALSE(finer("substeps", {50000, 100000}));           // past particles.substeps' range
  EXPECT_EQ(knob_step(*find_knob("substeps"), 200), 1.0 / 200);
  EXPECT_EQ(knob_step(*find_knob("particle_size"), 2), 2);
}

TEST(StudyKnobs, TheModelHasNoSolverIterations) {
  EXPECT_EQ(find_knob("iterations"), nullptr);
  EXPECT_NE(unknown_knob_message("solver_iterations").find("the particle model has no solver iterations"),
            std::string::npos);
  EXPECT_EQ(unknown_knob_message("substep"),
            "no knob 'substep' (known: compression, substeps, particle_size, blur_radius, blur_downsample, resolution)");
}

}  // namespace
}  // namespace bleedsim