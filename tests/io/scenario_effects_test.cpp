// Scenario files, the effects' tables: [particles] (and the particle keys of cuts and output)
// and [blur], each value read back or refused at its line with its key (docs/scenario-format.md).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/runtime/input_error.h"
#include "core/io/scenario.h"
#include "tests/io/scenario_text.h"

namespace bleedsim {
namespace {

using namespace test;

// ---- [particles] and the particle keys of cuts and output -------------------------------------

// A valid scene with an empty [particles] table last, so that text appended to it lands in
// [particles] (kParticlesEnd is the line it starts on).
const std::string kParticleBase =
    "[scene]\n"              //  1
    "width_px = 64\n"        //  2
    "height_px = 48\n"       //  3
    "width_mm = 16.0\n"      //  4
    "height_mm = 12.0\n"     //  5
    "duration_s = 0.5\n"     //  6
    "frame_rate_hz = 30\n"   //  7
    "[[cut]]\n"              //  8
    "x_mm = 8.0\n"           //  9
    "y_mm = 6.0\n"           // 10
    "[particles]\n";         // 11
constexpr int kParticlesEnd = 12;

std::string particles_with(const std::string& lines) { return kParticleBase + lines; }


// Every [particles] key set, one per line, and two cuts: one taking its flow from [particles],
// one giving its own. Its contact (k = 2e5, c = 50, γ = 80) is stable while
// 8·2e5·dt² + (16·50 − 2·80)·dt = 1.6e6·dt² + 640·dt < 4, up to
// dt = (−640 + √(640² + 16·1.6e6)) / (2·1.6e6) = (−640 + √26009600) / 3.2e6 = (−640 + 5099.96) / 3.2e6
//    = 1.394 ms; 25 Hz × 40 sub-steps is 1 ms, where the left side is 1.6 + 0.64 = 2.24.
const std::string kFullParticles =
    "[scene]\n"                                                //  1
    "name = \"particles-probe\"\n"                             //  2
    "width_px = 64\n"                                          //  3
    "height_px = 48\n"                                         //  4
    "width_mm = 16.0\n"                                        //  5
    "height_mm = 12.0\n"                                       //  6
    "duration_s = 1.0\n"                                       //  7
    "frame_rate_hz = 25\n"                                     //  8
    "\n"                                                       //  9
    "[particles]\n"                                            // 10
    "capacity = 4096\n"                                        // 11
    "diameter_mm = 0.25\n"                                     // 12
    "cell_mm = 0.5\n"                                          // 13
    "max_per_cell = 6\n"                                       // 14
    "rate_per_s = 800\n"                                       // 15
    "bleed_s = 1.5\n"                                          // 16
    "lifetime_s = 10\n"                                        // 17
    "fade_s = 2.5\n"                                           // 18
    "gravity_mm_s2 = [-100.5, 1500]\n"                         // 19
    "drag_per_s = 80\n"                                        // 20
    "stiffness_per_s2 = 2e5\n"                                 // 21
    "damping_per_s = 50\n"                                     // 22
    "max_speed_mm_s = 250\n"                                   // 23
    "substeps = 40\n"                                          // 24  1 ms, well inside the 1.394 ms limit (below)
    "jitter_mm = 0.02\n"                                       // 25
    "velocity_mm_s = [3, -4.5]\n"                              // 26
    "velocity_jitter_mm_s = 1.25\n"                            // 27
    "particle_volume_mm3 = 0.008\n"                            // 28  alone: the splat's volume, not the rate
    "splat_radius_mm = 0.4\n"                                  // 29
    "\n"                                                       // 30
    "[[cut]]\n"                                                // 31  its flow from [particles]
    "x_mm = 8.0\n"                                             // 32
    "y_mm = 2.0\n"                                             // 33
    "\n"                                                       // 34
    "[[cut]]\n"                                                // 35  its own
    "x_mm = 4.0\n"                                             // 36
    "y_mm = 3.0\n"                                             // 37
    "start_s = 0.5\n"                                          // 38
    "rate_per_s = 1200\n"                                      // 39
    "bleed_s = 0.25\n"                                         // 40
    "\n"                                                       // 41
    "[output]\n"                                               // 42
    "fields = [\"splat/thickness\", \"particles/position\"]\n";  // 43

TEST(ScenarioParticles, ReadsEveryParticleKey) {
  const Scenario scenario = parse_scenario(kFullParticles, kPath);
  const Scene& scene = scenario.scene;
  ASSERT_TRUE(scene.particles.has_value());
  const ParticleParams& p = *scene.particles;
  EXPECT_EQ(p.capacity, 4096);
  EXPECT_EQ(p.diameter_mm, 0.25);
  EXPECT_EQ(p.cell_mm, 0.5);
  EXPECT_EQ(p.max_per_cell, 6);
  EXPECT_EQ(p.rate_per_s, 800.0);  // particle_volume_mm3 (line 28) without volume_mm3_per_s leaves it alone
  EXPECT_EQ(p.bleed_s, 1.5);
  EXPECT_EQ(p.lifetime_s, 10.0);
  EXPECT_EQ(p.fade_s, 2.5);
  EXPECT_EQ(p.gravity_x_mm_s2, -100.5);
  EXPECT_EQ(p.gravity_y_mm_s2, 1500.0);
  EXPECT_EQ(p.drag_per_s, 80.0);
  EXPECT_EQ(p.stiffness_per_s2, 2e5);
  EXPECT_EQ(p.damping_per_s, 50.0);
  EXPECT_EQ(p.max_speed_mm_s, 250.0);
  EXPECT_EQ(p.substeps, 40);
  EXPECT_EQ(p.jitter_mm, 0.02);
  EXPECT_EQ(p.velocity_x_mm_s, 3.0);
  EXPECT_EQ(p.velocity_y_mm_s, -4.5);
  EXPECT_EQ(p.velocity_jitter_mm_s, 1.25);
  EXPECT_EQ(p.particle_volume_mm3, 0.008);
  EXPECT_EQ(p.splat_radius_mm, 0.4);
  EXPECT_FALSE(scene.spread.has_value());  // [particles] declares the particle flow alone

  ASSERT_EQ(scene.cuts.size(), 2u);
  EXPECT_EQ(scene.cuts[0].rate_per_s, 800.0);  // from [particles]
  EXPECT_EQ(scene.cuts[0].bleed_s, 1.5);       // from [particles]
  EXPECT_EQ(scene.cuts[1].start_s, 0.5);
  EXPECT_EQ(scene.cuts[1].rate_per_s, 1200.0);
  EXPECT_EQ(scene.cuts[1].bleed_s, 0.25);

  EXPECT_EQ(scenario.output.fields, (std::vector<std::string>{"splat/thickness", "particles/position"}));

  EXPECT_EQ(scenario.place_of("particles").line, 10);
  EXPECT_EQ(scenario.place_of("particles.capacity").line, 11);
  EXPECT_EQ(scenario.place_of("particles.gravity_mm_s2").line, 19);
  EXPECT_EQ(scenario.place_of("particles.max_speed_mm_s").line, 23);
  EXPECT_EQ(scenario.place_of("particles.substeps").line, 24);
  EXPECT_EQ(scenario.place_of("particles.particle_volume_mm3").line, 28);
  EXPECT_EQ(scenario.place_of("particles.splat_radius_mm").line, 29);
  EXPECT_EQ(scenario.place_of("cut[1].rate_per_s").line, 39);
}

TEST(ScenarioParticles, AnEmptyTableTakesTheDocumentedDefaults) {
  const Scenario scenario = parse_scenario(kParticleBase, kPath);
  const Scene& scene = scenario.scene;
  ASSERT_TRUE(scene.particles.has_value());
  const ParticleParams& p = *scene.particles;
  // The values docs/scenario-format.md lists, written out so that a changed default shows here.
  EXPECT_EQ(p.capacity, 65536);
  EXPECT_EQ(p.diameter_mm, 0.2);
  EXPECT_EQ(p.cell_mm, 0.0);  // 0: the diameter
  EXPECT_EQ(p.max_per_cell, 8);
  EXPECT_EQ(p.rate_per_s, 500.0);
  EXPECT_EQ(p.bleed_s, 2.0);
  EXPECT_EQ(p.lifetime_s, 30.0);
  EXPECT_EQ(p.fade_s, 1.0);
  EXPECT_EQ(p.gravity_x_mm_s2, 0.0);
  EXPECT_EQ(p.gravity_y_mm_s2, 1000.0);  // down the panel
  EXPECT_EQ(p.drag_per_s, 100.0);
  EXPECT_EQ(p.stiffness_per_s2, 4.0e5);
  EXPECT_EQ(p.damping_per_s, 100.0);
  EXPECT_EQ(p.max_speed_mm_s, 100.0);
  EXPECT_EQ(p.substeps, 40);
  EXPECT_EQ(p.jitter_mm, 0.05);
  EXPECT_EQ(p.velocity_x_mm_s, 0.0);
  EXPECT_EQ(p.velocity_y_mm_s, 0.0);
  EXPECT_EQ(p.velocity_jitter_mm_s, 5.0);
  EXPECT_EQ(p.particle_volume_mm3, 0.004);
  EXPECT_EQ(p.splat_radius_mm, 0.0);  // 0: the diameter
  // A cut that gives no flow of its own takes [particles]' defaults.
  ASSERT_EQ(scene.cuts.size(), 1u);
  EXPECT_EQ(scene.cuts[0].rate_per_s, 500.0);
  EXPECT_EQ(scene.cuts[0].bleed_s, 2.0);
  EXPECT_TRUE(scenario.output.fields.empty());
}

TEST(ScenarioParticles, FadeDefaultsToTheLifetimeWhenTheLifetimeIsShorter) {
  const Scenario scenario = parse_scenario(particles_with("lifetime_s = 0.5\n"), kPath);
  const Scene& scene = scenario.scene;
  EXPECT_EQ(scene.particles->lifetime_s, 0.5);
  EXPECT_EQ(scene.particles->fade_s, 0.5);
}

TEST(ScenarioParticles, EachKeyOutOfRangeIsRefusedAtItsLine) {
  struct Case {
    const char* line;
    const char* key;
    const char* gist;
  };
  const Case cases[] = {
      {"capacity = 0", "particles.capacity", "must be between 1 and 268435456 (got 0)"},
      {"capacity = 268435457", "particles.capacity", "must be between 1 and 268435456 (got 268435457)"},
      {"capacity = 1024.0", "particles.capacity", "expected an integer, got a floating-point number"},
      {"diameter_mm = -1", "particles.diameter_mm", "must be greater than 0 and at most 100 (got -1)"},
      {"diameter_mm = 0", "particles.diameter_mm", "must be greater than 0 and at most 100 (got 0)"},
      {"diameter_mm = \"0.2\"", "particles.diameter_mm", "expected a number, got a string"},
      {"cell_mm = 0.1", "particles.cell_mm", "must be 0 (the diameter) or at least diameter_mm, 0.2 mm (got 0.1)"},
      {"max_per_cell = 0", "particles.max_per_cell", "must be between 1 and 1024 (got 0)"},
      {"rate_per_s = -5", "particles.rate_per_s", "must be between 0 and 1e+08 (got -5)"},
      {"rate_per_s = 1.5e8", "particles.rate_per_s", "must be between 0 and 1e+08 (got 1.5e+08)"},
      {"volume_mm3_per_s = -1", "particles.volume_mm3_per_s", "must be between 0 and 1e+06 (got -1)"},
      {"particle_volume_mm3 = 0", "particles.particle_volume_mm3",
       "must be greater than 0 and at most 1e+06 (got 0)"},
      {"particle_volume_mm3 = 2e6", "particles.particle_volume_mm3",
       "must be greater than 0 and at most 1e+06 (got 2e+06)"},
      {"bleed_s = -1", "particles.bleed_s", "must be between 0 and 86400 (got -1)"},
      {"lifetime_s = 0", "particles.lifetime_s", "must be greater than 0 and at most 86400 (got 0)"},
      {"lifetime_s = nan", "particles.lifetime_s", "must be a finite number (got nan)"},
      {"fade_s = 0", "particles.fade_s", "must be greater than 0 and at most 86400 (got 0)"},
      // 30: the default lifetime.
      {"fade_s = 30.5", "particles.fade_s", "must be at most lifetime_s, 30 s (got 30.5)"},
      {"drag_per_s = -1", "particles.drag_per_s", "must be between 0 and 1e+06 (got -1)"},
      {"stiffness_per_s2 = 0", "particles.stiffness_per_s2", "must be greater than 0 and at most 1e+12 (got 0)"},
      {"damping_per_s = -1", "particles.damping_per_s", "must be between 0 and 1e+06 (got -1)"},
      {"max_speed_mm_s = 0", "particles.max_speed_mm_s", "must be greater than 0 and at most 100000 (got 0)"},
      {"max_speed_mm_s = 2e5", "particles.max_speed_mm_s", "must be greater than 0 and at most 100000 (got 200000)"},
      {"substeps = 0", "particles.substeps", "must be between 1 and 100000 (got 0)"},
      {"substeps = 33.0", "particles.substeps", "expected an integer, got a floating-point number"},
      {"jitter_mm = -0.1", "particles.jitter_mm", "must be between 0 and 100 (got -0.1)"},
      {"velocity_jitter_mm_s = -1", "particles.velocity_jitter_mm_s", "must be between 0 and 100000 (got -1)"},
      {"splat_radius_mm = -0.1", "particles.splat_radius_mm", "must be between 0 and 100 (got -0.1)"},
      {"splat_radius_mm = 100.5", "particles.splat_radius_mm", "must be between 0 and 100 (got 100.5)"},
  };
  for (const Case& c : cases)
    EXPECT_TRUE(refused_at(particles_with(std::string(c.line) + "\n"), kParticlesEnd, c.key, c.gist)) << c.line;
  // The place points at the value, after `key = `.
  EXPECT_EQ(refused_column(particles_with("capacity = 0\n")), 12);
}

TEST(ScenarioParticles, FadeLongerThanTheLifetime) {
  EXPECT_TRUE(refused_at(particles_with("lifetime_s = 5\nfade_s = 6\n"), kParticlesEnd + 1, "particles.fade_s",
                         "must be at most lifetime_s, 5 s (got 6)"));
  EXPECT_EQ(parse_scenario(particles_with("lifetime_s = 5\nfade_s = 5\n"), kPath).scene.particles->fade_s, 5.0);
}

TEST(ScenarioParticles, CellSmallerThanTheDiameter) {
  EXPECT_TRUE(refused_at(particles_with("diameter_mm = 0.5\ncell_mm = 0.4\n"), kParticlesEnd + 1,
                         "particles.cell_mm", "must be 0 (the diameter) or at least diameter_mm, 0.5 mm (got 0.4)"));
  // A cell as large as a particle is the smallest allowed.
  EXPECT_EQ(parse_scenario(particles_with("diameter_mm = 0.5\ncell_mm = 0.5\n"), kPath).scene.particles->cell_mm, 0.5);
}

TEST(ScenarioParticles, VectorsNeedTwoFiniteNumbersAndNameTheBadComponent) {
  const int line = kParticlesEnd;
  EXPECT_TRUE(refused_at(particles_with("gravity_mm_s2 = [0]\n"), line, "particles.gravity_mm_s2",
                         "expected [x, y], two numbers, got an array of 1 element"));
  EXPECT_TRUE(refused_at(particles_with("gravity_mm_s2 = []\n"), line, "particles.gravity_mm_s2",
                         "expected [x, y], two numbers, got an empty array"));
  EXPECT_TRUE(refused_at(particles_with("velocity_mm_s = [1, 2, 3]\n"), line, "particles.velocity_mm_s",
                         "expected [x, y], two numbers, got an array of 3 elements"));
  EXPECT_TRUE(refused_at(particles_with("gravity_mm_s2 = 9.8\n"), line, "particles.gravity_mm_s2",
                         "expected [x, y], two numbers, got a floating-point number"));
  EXPECT_TRUE(refused_at(particles_with("gravity_mm_s2 = [0, \"down\"]\n"), line, "particles.gravity_mm_s2.y",
                         "expected a number, got a string"));
  EXPECT_TRUE(refused_at(particles_with("gravity_mm_s2 = [inf, 0]\n"), line, "particles.gravity_mm_s2.x",
                         "must be a finite number (got inf)"));
  EXPECT_TRUE(refused_at(particles_with("gravity_mm_s2 = [0, nan]\n"), line, "particles.gravity_mm_s2.y",
                         "must be a finite number (got nan)"));
  EXPECT_TRUE(refused_at(particles_with("gravity_mm_s2 = [0, 2e6]\n"), line, "particles.gravity_mm_s2.y",
                         "must be between -1e+06 and 1e+06 (got 2e+06)"));
  EXPECT_TRUE(refused_at(particles_with("velocity_mm_s = [0, -2e5]\n"), line, "particles.velocity_mm_s.y",
                         "must be between -100000 and 100000 (got -200000)"));
  // Two bad components: the first is the one refused, whatever order the compiler evaluates in.
  EXPECT_TRUE(refused_at(particles_with("velocity_mm_s = [\"a\", \"b\"]\n"), line, "particles.velocity_mm_s.x",
                         "expected a number, got a string"));
  // A whole-vector problem points at the vector; a component's at the component.
  EXPECT_EQ(refused_column(particles_with("gravity_mm_s2 = [0]\n")), 17);
  EXPECT_EQ(refused_column(particles_with("gravity_mm_s2 = [0, \"down\"]\n")), 21);
}

TEST(ScenarioParticles, RateAndVolumeTogetherAreRefused) {
  EXPECT_TRUE(refused_at(particles_with("rate_per_s = 100\nvolume_mm3_per_s = 2.0\nparticle_volume_mm3 = 0.004\n"),
                         kParticlesEnd + 1, "particles.volume_mm3_per_s",
                         "give either rate_per_s or volume_mm3_per_s, not both"));
}

TEST(ScenarioParticles, VolumeAndParticleVolumeNeedEachOther) {
  // A volume rate cannot be turned into a count of particles without the volume of one.
  EXPECT_TRUE(refused_at(particles_with("volume_mm3_per_s = 2.0\n"), kParticlesEnd, "particles.volume_mm3_per_s",
                         "needs particle_volume_mm3 beside it"));
  // A particle volume alone is the blood each particle's splat spreads; the rate keeps its default.
  const Scenario scenario = parse_scenario(particles_with("particle_volume_mm3 = 0.01\n"), kPath);
  const Scene& scene = scenario.scene;
  EXPECT_EQ(scene.particles->particle_volume_mm3, 0.01);
  EXPECT_EQ(scene.particles->rate_per_s, 500.0);
  EXPECT_EQ(scenario.place_of("particles.particle_volume_mm3").line, kParticlesEnd);
}

TEST(ScenarioParticles, VolumeOverParticleVolumeGivesTheRate) {
  const Scenario scenario = parse_scenario(particles_with("volume_mm3_per_s = 2.0\nparticle_volume_mm3 = 0.004\n"), kPath);
  const Scene& scene = scenario.scene;
  EXPECT_DOUBLE_EQ(scene.particles->rate_per_s, 500.0);  // 2 mm³/s of 0.004 mm³ particles
  EXPECT_DOUBLE_EQ(scene.cuts[0].rate_per_s, 500.0);     // and cuts take it as their default
  // 1e5 mm³/s of 2⁻¹⁰ mm³ particles is 102,400,000 a second: more than the 1e8 allowed.
  EXPECT_TRUE(refused_at(particles_with("volume_mm3_per_s = 1e5\nparticle_volume_mm3 = 0.0009765625\n"),
                         kParticlesEnd, "particles.volume_mm3_per_s",
                         "gives 1.024e+08 particles per second; at most 1e+08"));
}

// The contact is stable while 8k·dt² + (16c − 2γ)·dt < 4 (core/effects/particle_model.h, z = 8 design
// contacts). With stiffness k = 3.25e5/s², damping c = 100/s and drag γ = 100/s that is
// 2.6e6·dt² + 1400·dt < 4, and at dt = 1 ms the left side is 2.6 + 1.4 = 4: the limit is exactly
// 1 ms. In floating point too: b² + 16a = 1400² + 16·2.6e6 = 4.356e7 = 6600², so the root
// (−1400 + 6600) / (2·2.6e6) = 5200 / 5.2e6 is one correctly rounded division, equal to 1/1000.
// (The dashpot's own condition, 8c·dt < 2 + γ·dt, allows up to 2/(8c − γ) = 2/700 = 2.857 ms. The
// old six-contact rule, 1.95e6·dt² + 1000·dt = 2.95 at 1 ms, would let every sub-step below pass.)
const std::string kStiffContact = "stiffness_per_s2 = 3.25e5\n";  // damping and drag keep their 100/s

TEST(ScenarioParticles, SubStepPastTheStabilityLimitIsRefusedWithTheLimitAndTheSubStepsNeeded) {
  // 30 Hz × 33 sub-steps: 1/990 s = 1.0101 ms, past the limit (2.6e6·1.0203e-6 + 1.4·1.0101 =
  // 2.6528 + 1.4141 = 4.067); n sub-steps stay inside it while 1/(30·n) < 1 ms, that is n > 33.3:
  // at least 34.
  EXPECT_TRUE(refused_at(particles_with(kStiffContact + "substeps = 33\n"), kParticlesEnd + 1, "particles.substeps",
                         "a sub-step of 1.01 ms is past the contact model's stability limit of 1 ms (stiffness "
                         "3.25e+05/s², damping 100/s, drag 100/s); use at least 34 sub-steps per frame, or a softer "
                         "contact"));
}

TEST(ScenarioParticles, SubStepJustInsideTheStabilityLimitIsAccepted) {
  // 34 sub-steps: 1/1020 s = 0.9804 ms; 2.6e6·9.612e-7 + 1.4·0.9804 = 2.499 + 1.373 = 3.872 < 4.
  EXPECT_EQ(parse_scenario(particles_with(kStiffContact + "substeps = 34\n"), kPath).scene.particles->substeps, 34);
}

TEST(ScenarioParticles, SubStepExactlyAtTheStabilityLimitIsRefused) {
  // 50 Hz × 20 sub-steps: exactly 1 ms, where the left side is exactly 4. The condition is strict,
  // so 21 are needed: 1/1050 s = 0.9524 ms, 2.6e6·9.070e-7 + 1.4·0.9524 = 2.358 + 1.333 = 3.692.
  const std::string at_50_hz = with_line(particles_with(kStiffContact + "substeps = 20\n"), 7, "frame_rate_hz = 50");
  EXPECT_TRUE(refused_at(at_50_hz, kParticlesEnd + 1, "particles.substeps",
                         "a sub-step of 1 ms is past the contact model's stability limit of 1 ms (stiffness 3.25e+05/s², "
                         "damping 100/s, drag 100/s); use at least 21 sub-steps per frame"));
  EXPECT_EQ(parse_scenario(with_line(particles_with(kStiffContact + "substeps = 21\n"), 7, "frame_rate_hz = 50"),
                           kPath).scene.particles->substeps, 21);
}

TEST(ScenarioParticles, DefaultSubStepsAtALowFrameRateAreRefusedAtTheTable) {
  // The default contact (k = 4e5, c = γ = 100): 3.2e6·dt² + 1400·dt < 4 up to
  // dt = (−1400 + √(1400² + 16·3.2e6)) / (2·3.2e6) = (−1400 + √5.316e7) / 6.4e6
  //    = (−1400 + 7291.09) / 6.4e6 = 0.92048 ms.
  // At 25 Hz the default 40 sub-steps are 1/1000 s = 1 ms (3.2 + 1.4 = 4.6); inside needs
  // n > 1/(25 · 0.92048 ms) = 43.46: 44 (1/1100 s = 0.9091 ms: 2.645 + 1.273 = 3.917; 43 would be
  // 1/1075 s = 0.9302 ms: 2.769 + 1.302 = 4.071). substeps is not written, so the refusal is placed
  // at the [particles] header.
  const std::string at_25_hz = with_line(kParticleBase, 7, "frame_rate_hz = 25");
  EXPECT_TRUE(refused_at(at_25_hz, 11, "particles.substeps",
                         "a sub-step of 1 ms is past the contact model's stability limit of 0.9205 ms (stiffness "
                         "4e+05/s², damping 100/s, drag 100/s); use at least 44 sub-steps per frame"));
  EXPECT_TRUE(refused_at(with_line(particles_with("substeps = 43\n"), 7, "frame_rate_hz = 25"), kParticlesEnd,
                         "particles.substeps", "use at least 44 sub-steps per frame"));
  EXPECT_EQ(parse_scenario(with_line(particles_with("substeps = 44\n"), 7, "frame_rate_hz = 25"), kPath)
                .scene.particles->substeps, 44);
}

TEST(ScenarioParticles, AFilmThickerThanTheSplatCanSumIsRefused) {
  // 100 mm³ over the default splat radius (the 0.2 mm diameter): 100 / (π·0.04/3) = 2387 mm under
  // the centre, past the 1e9 units of 2⁻²⁴ mm (59.6 mm) one deposit may hold.
  EXPECT_TRUE(refused_at(particles_with("particle_volume_mm3 = 100\n"), kParticlesEnd,
                         "particles.particle_volume_mm3",
                         "a particle of 100 mm³ over a splat radius of 0.2 mm is 2387 mm thick under its centre; "
                         "the splat holds at most 59.6 mm per particle"));
  EXPECT_NO_THROW(parse_scenario(particles_with("particle_volume_mm3 = 2\n"), "x.toml"));  // 47.7 mm: fits
}

TEST(ScenarioParticles, ParticlesLargerThanThePanel) {
  EXPECT_TRUE(refused_at(particles_with("diameter_mm = 12\n"), kParticlesEnd, "particles.diameter_mm",
                         "particles of 12 mm do not fit in a 16 x 12 mm panel"));
}

TEST(ScenarioParticles, LifetimeTooLongToCountInSteps) {
  // 86400 s × 30 Hz × 1000 sub-steps = 2.592e9 steps.
  EXPECT_TRUE(refused_at(particles_with("lifetime_s = 86400\nsubsteps = 1000\n"), kParticlesEnd,
                         "particles.lifetime_s", "a lifetime of 8.64e+04 s is 2.592e+09 steps; at most 2e9"));
}

TEST(ScenarioParticles, CollisionGridTooLargeIsPlacedAtTheTableWhenCellIsNotWritten) {
  // A 10 m panel in 0.15 mm cells: 66667² = 4.44e9 cells.
  const std::string huge = with_line(with_line(particles_with("diameter_mm = 0.15\n"), 4, "width_mm = 10000"), 5,
                                     "height_mm = 10000");
  EXPECT_TRUE(refused_at(huge, 11, "particles.cell_mm", "the collision grid would have 4.444e+09 cells; at most 4e9"));
}

TEST(ScenarioParticles, UnknownKeySuggestsTheNearest) {
  EXPECT_TRUE(refused_at(particles_with("stifness_per_s2 = 1e5\n"), kParticlesEnd, "particles.stifness_per_s2",
                         "unknown key; did you mean 'stiffness_per_s2'?"));
  EXPECT_TRUE(refused_at(particles_with("gravity = [0, 9.8]\n"), kParticlesEnd, "particles.gravity",
                         "unknown key (known here: capacity diameter_mm cell_mm"));
}

TEST(ScenarioParticles, CutRateAndBleedOverrideTheTablesDefaults) {
  const Scenario scenario = parse_scenario(particles_with("rate_per_s = 300\nbleed_s = 4\n") +
                                         "[[cut]]\nx_mm = 1.0\ny_mm = 1.0\nrate_per_s = 0\n"
                                         "[[cut]]\nx_mm = 2.0\ny_mm = 2.0\nbleed_s = 0.5\n",
                                     kPath);
  const Scene& scene = scenario.scene;
  ASSERT_EQ(scene.cuts.size(), 3u);
  EXPECT_EQ(scene.cuts[0].rate_per_s, 300.0);  // from [particles]
  EXPECT_EQ(scene.cuts[0].bleed_s, 4.0);
  EXPECT_EQ(scene.cuts[1].rate_per_s, 0.0);    // a cut that does not bleed particles
  EXPECT_EQ(scene.cuts[1].bleed_s, 4.0);
  EXPECT_EQ(scene.cuts[2].rate_per_s, 300.0);
  EXPECT_EQ(scene.cuts[2].bleed_s, 0.5);
}

TEST(ScenarioParticles, CutRateOrBleedOutOfRange) {
  // The new [[cut]] starts on kParticlesEnd.
  EXPECT_TRUE(refused_at(particles_with("[[cut]]\nx_mm = 1.0\ny_mm = 1.0\nrate_per_s = -1\n"), kParticlesEnd + 3,
                         "cut[1].rate_per_s", "must be between 0 and 1e+08 (got -1)"));
  EXPECT_TRUE(refused_at(particles_with("[[cut]]\nx_mm = 1.0\ny_mm = 1.0\nbleed_s = -0.5\n"), kParticlesEnd + 3,
                         "cut[1].bleed_s", "must be between 0 and 86400 (got -0.5)"));
}

TEST(ScenarioParticles, CutFlowKeysWithoutParticlesAreRefusedAtTheirLine) {
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "rate_per_s = 100"), 16, "cut[1].rate_per_s",
                         "has no effect: this scene declares no [particles]"));
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "bleed_s = 1.0"), 16, "cut[1].bleed_s",
                         "has no effect: this scene declares no [particles]"));
}

TEST(ScenarioParticles, OutputFieldsNameParticleFieldsOnlyWithParticles) {
  EXPECT_TRUE(refused_at(kBase + "fields = [\"particles/position\"]\n", kEnd, "output.fields[0]",
                         "'particles/position' needs the [particles] effect, which this scene does not declare"));
  const std::string all =
      "[output]\nfields = [\"splat/thickness\", \"particles/accounting\", \"particles/position\", "
      "\"particles/velocity\", \"particles/age\"]\n";
  EXPECT_EQ(parse_scenario(particles_with(all), kPath).output.fields,
            (std::vector<std::string>{"splat/thickness", "particles/accounting", "particles/position",
                                      "particles/velocity", "particles/age"}));
  // The splat's film exists only with particles too.
  EXPECT_TRUE(refused_at(kBase + "fields = [\"splat/thickness\"]\n", kEnd, "output.fields[0]",
                         "'splat/thickness' needs the [particles] effect, which this scene does not declare"));
}

// ---- [blur]: the blur of the particles' film ---------------------------------------------------

// kParticleBase with an empty [blur] after its [particles], so that text appended to it lands in
// [blur] (kBlurEnd is the line it starts on).
const std::string kBlurBase = kParticleBase + "[blur]\n";  // 12
constexpr int kBlurHeader = kParticlesEnd;                  // 12
constexpr int kBlurEnd = kBlurHeader + 1;                   // 13

std::string blur_with(const std::string& lines) { return kBlurBase + lines; }

TEST(ScenarioBlur, AcceptsTheBaseTextThatTheBlurTestsBreak) {
  ASSERT_EQ(int(lines_of(kBlurBase).size()), kBlurEnd - 1);
  EXPECT_TRUE(parse_scenario(kBlurBase, kPath).scene.blur.has_value());
  // Without [blur] a scene with particles does not blur its film.
  EXPECT_FALSE(parse_scenario(kParticleBase, kPath).scene.blur.has_value());
}

TEST(ScenarioBlur, AnEmptyTableTakesTheDocumentedDefaults) {
  const Scenario scenario = parse_scenario(kBlurBase, kPath);
  const Scene& scene = scenario.scene;
  ASSERT_TRUE(scene.blur.has_value());
  // The values docs/scenario-format.md lists, written out so that a changed default shows here.
  EXPECT_EQ(scene.blur->downsample, 2);
  EXPECT_EQ(scene.blur->radius_px, 4);
  EXPECT_EQ(scene.blur->sigma_px, 2.0);  // max(0.5, radius_px / 2)
  EXPECT_EQ(scenario.place_of("blur").line, kBlurHeader);
  EXPECT_TRUE(scenario.output.fields.empty());
}

TEST(ScenarioBlur, ReadsEveryBlurKey) {
  const Scenario scenario = parse_scenario(blur_with("downsample = 4\n"   // 13
                                               "radius_px = 7\n"    // 14
                                               "sigma_px = 3.25\n"  // 15
                                               "[output]\n"         // 16
                                               "fields = [\"splat/thickness\", \"blur/thickness\"]\n"),  // 17
                                     kPath);
  const Scene& scene = scenario.scene;
  ASSERT_TRUE(scene.blur.has_value());
  EXPECT_EQ(scene.blur->downsample, 4);
  EXPECT_EQ(scene.blur->radius_px, 7);
  EXPECT_EQ(scene.blur->sigma_px, 3.25);
  EXPECT_EQ(scenario.output.fields, (std::vector<std::string>{"splat/thickness", "blur/thickness"}));
  EXPECT_EQ(scenario.place_of("blur").line, kBlurHeader);
  EXPECT_EQ(scenario.place_of("blur.downsample").line, kBlurEnd);
  EXPECT_EQ(scenario.place_of("blur.radius_px").line, kBlurEnd + 1);
  EXPECT_EQ(scenario.place_of("blur.sigma_px").line, kBlurEnd + 2);
  // A place points at the value, after `key = `.
  EXPECT_EQ(scenario.place_of("blur.downsample").column, 14);
}

TEST(ScenarioBlur, EveryAllowedValueAtTheEndsOfItsRangeIsAccepted) {
  EXPECT_EQ(parse_scenario(blur_with("downsample = 1\n"), kPath).scene.blur->downsample, 1);
  EXPECT_EQ(parse_scenario(blur_with("downsample = 2\n"), kPath).scene.blur->downsample, 2);
  EXPECT_EQ(parse_scenario(blur_with("downsample = 4\n"), kPath).scene.blur->downsample, 4);
  EXPECT_EQ(parse_scenario(blur_with("radius_px = 0\n"), kPath).scene.blur->radius_px, 0);
  EXPECT_EQ(parse_scenario(blur_with("radius_px = 64\n"), kPath).scene.blur->radius_px, 64);
  EXPECT_EQ(parse_scenario(blur_with("sigma_px = 64\n"), kPath).scene.blur->sigma_px, 64.0);  // an integer: a number
  EXPECT_EQ(parse_scenario(blur_with("sigma_px = 1e-3\n"), kPath).scene.blur->sigma_px, 1e-3);
}

TEST(ScenarioBlur, SigmaDefaultsToHalfTheRadiusButNotBelowHalfAPixel) {
  const auto sigma = [](const std::string& lines) { return parse_scenario(blur_with(lines), kPath).scene.blur->sigma_px; };
  EXPECT_EQ(sigma("radius_px = 10\n"), 5.0);
  EXPECT_EQ(sigma("radius_px = 3\n"), 1.5);
  EXPECT_EQ(sigma("radius_px = 64\n"), 32.0);
  EXPECT_EQ(sigma("radius_px = 1\n"), 0.5);
  EXPECT_EQ(sigma("radius_px = 0\n"), 0.5);  // radius_px / 2 = 0 would be no Gaussian at all
  // A sigma given is taken as it is, whatever the radius.
  EXPECT_EQ(sigma("radius_px = 0\nsigma_px = 10\n"), 10.0);
  EXPECT_EQ(sigma("radius_px = 10\nsigma_px = 0.25\n"), 0.25);
}

TEST(ScenarioBlur, EachKeyOutOfRangeIsRefusedAtItsLine) {
  struct Case {
    const char* line;
    const char* key;
    const char* gist;
  };
  const Case cases[] = {
      {"downsample = 0", "blur.downsample", "must be 1, 2 or 4 (got 0)"},
      {"downsample = 3", "blur.downsample", "must be 1, 2 or 4 (got 3)"},
      {"downsample = 5", "blur.downsample", "must be 1, 2 or 4 (got 5)"},
      {"downsample = -2", "blur.downsample", "must be 1, 2 or 4 (got -2)"},
      {"downsample = 2.0", "blur.downsample", "expected an integer, got a floating-point number"},
      {"radius_px = -1", "blur.radius_px", "must be between 0 and 64 (got -1)"},
      {"radius_px = 65", "blur.radius_px", "must be between 0 and 64 (got 65)"},
      {"radius_px = 4.0", "blur.radius_px", "expected an integer, got a floating-point number"},
      {"sigma_px = 0", "blur.sigma_px", "must be greater than 0 and at most 64 (got 0)"},
      {"sigma_px = -1.5", "blur.sigma_px", "must be greater than 0 and at most 64 (got -1.5)"},
      {"sigma_px = 65", "blur.sigma_px", "must be greater than 0 and at most 64 (got 65)"},
      {"sigma_px = 64.5", "blur.sigma_px", "must be greater than 0 and at most 64 (got 64.5)"},
      {"sigma_px = nan", "blur.sigma_px", "must be a finite number (got nan)"},
      {"sigma_px = \"2\"", "blur.sigma_px", "expected a number, got a string"},
  };
  for (const Case& c : cases)
    EXPECT_TRUE(refused_at(blur_with(std::string(c.line) + "\n"), kBlurEnd, c.key, c.gist)) << c.line;
  // The place points at the value, after `key = `, for the refusal of 3 as for the range's.
  EXPECT_EQ(refused_column(blur_with("downsample = 3\n")), 14);
  EXPECT_EQ(refused_column(blur_with("downsample = 5\n")), 14);
  EXPECT_EQ(refused_column(blur_with("sigma_px = 0\n")), 12);
  // A bad key below good ones is placed at its own line.
  EXPECT_TRUE(refused_at(blur_with("downsample = 4\nradius_px = 8\nsigma_px = 0\n"), kBlurEnd + 2, "blur.sigma_px",
                         "must be greater than 0 and at most 64 (got 0)"));
}

TEST(ScenarioBlur, WithoutParticlesIsRefusedAtItsHeader) {
  const std::string gist = "the blur stage reads splat/thickness, which the splat stage writes; a scene calls for "
                           "that stage with a [particles] table, and this one has none";
  // kBase declares the spread but no particles.
  EXPECT_TRUE(refused_at(kBase + "[blur]\n", kEnd, "blur", gist));
  // At the header even when the table sets keys, good or bad.
  EXPECT_TRUE(refused_at(kBase + "[blur]\nradius_px = 2\n", kEnd, "blur", gist));
  EXPECT_TRUE(refused_at(kBase + "[blur]\nsigma_px = 0\n", kEnd, "blur", gist));
  EXPECT_EQ(refused_column(kBase + "[blur]\n"), 1);
}

TEST(ScenarioBlur, MayBeWrittenBeforeItsParticles) {
  // Tables are read by name, not in file order: a [blur] above its [particles] is the same scene.
  const std::string text =
      "[scene]\n"
      "width_px = 64\n"
      "height_px = 48\n"
      "width_mm = 16.0\n"
      "height_mm = 12.0\n"
      "duration_s = 0.5\n"
      "[blur]\n"
      "radius_px = 6\n"
      "[particles]\n"
      "[[cut]]\n"
      "x_mm = 8.0\n"
      "y_mm = 6.0\n";
  const Scenario scenario = parse_scenario(text, kPath);
  const Scene& scene = scenario.scene;
  ASSERT_TRUE(scene.blur.has_value());
  EXPECT_EQ(scene.blur->radius_px, 6);
  EXPECT_EQ(scene.blur->sigma_px, 3.0);
  EXPECT_EQ(scenario.place_of("blur").line, 7);
}

TEST(ScenarioBlur, WrittenAsAValueInsteadOfATable) {
  EXPECT_TRUE(refused_at("blur = 2\n" + kParticleBase, 1, "blur", "expected a table, got an integer"));
}

TEST(ScenarioBlur, UnknownKeySuggestsTheNearest) {
  EXPECT_TRUE(refused_at(blur_with("radius_pix = 3\n"), kBlurEnd, "blur.radius_pix",
                         "unknown key; did you mean 'radius_px'?"));
  EXPECT_TRUE(refused_at(blur_with("down_sample = 2\n"), kBlurEnd, "blur.down_sample",
                         "unknown key; did you mean 'downsample'?"));
  EXPECT_TRUE(refused_at(blur_with("sigma_mm = 0.1\n"), kBlurEnd, "blur.sigma_mm",
                         "unknown key; did you mean 'sigma_px'?"));
  EXPECT_TRUE(refused_at(blur_with("strength = 2\n"), kBlurEnd, "blur.strength",
                         "unknown key (known here: downsample radius_px sigma_px)"));
}

TEST(ScenarioBlur, OutputFieldsNameTheBlurredFilmOnlyWithBlur) {
  const std::string gist = "'blur/thickness' needs the [blur] effect, which this scene does not declare";
  // With particles but no [blur]: the splat's film exists, the blurred one does not.
  EXPECT_TRUE(refused_at(particles_with("[output]\nfields = [\"blur/thickness\"]\n"), kParticlesEnd + 1,
                         "output.fields[0]", gist));
  EXPECT_TRUE(refused_at(particles_with("[output]\nfields = [\n  \"splat/thickness\",\n  \"blur/thickness\",\n]\n"),
                         kParticlesEnd + 3, "output.fields[1]", gist));
  // With neither.
  EXPECT_TRUE(refused_at(kBase + "fields = [\"blur/thickness\"]\n", kEnd, "output.fields[0]", gist));
  // With [blur], alone or beside every other field of the scene.
  EXPECT_EQ(parse_scenario(blur_with("[output]\nfields = [\"blur/thickness\"]\n"), kPath).output.fields,
            std::vector<std::string>{"blur/thickness"});
  const std::string all =
      "[output]\nfields = [\"splat/thickness\", \"blur/thickness\", \"particles/accounting\", "
      "\"particles/position\", \"particles/velocity\", \"particles/age\"]\n";
  EXPECT_EQ(parse_scenario(blur_with(all), kPath).output.fields,
            (std::vector<std::string>{"splat/thickness", "blur/thickness", "particles/accounting",
                                      "particles/position", "particles/velocity", "particles/age"}));
  EXPECT_TRUE(refused_at(blur_with("[output]\nfields = [\n  \"blur/thickness\",\n  \"blur/thickness\",\n]\n"),
                         kBlurEnd + 3, "output.fields[1]", "'blur/thickness' is listed twice"));
}

}  // namespace
}  // namespace bleedsim
