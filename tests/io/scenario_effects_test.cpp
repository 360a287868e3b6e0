// Scenario files, the particles' table: [particles] and the particle keys of cuts and output, each
// value read back or refused at its line with its key (docs/scenario-format.md; [blur]:
// scenario_blur_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/spread/spread_params.h"
#include "core/io/scenario.h"
#include "core/runtime/input_error.h"
#include "tests/io/scenario_text.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

using namespace test;
namespace fs = std::filesystem;

// Every [particles] key set, one per line, and two cuts: one taking its wound's flow from
// [particles], one giving its own. Its contact (docs/particles.md): d = 0.25 mm, V = 0.008 mm³,
// cohesion 40·0.25/0.008 = 1250 mm/s², gravity |(−100.5, 1500)| = 1503.4 mm/s², a design depth of
// 10 mm, compression 0.04: k = (1503.4·10 + 1250·0.25)/(0.04·0.0625) = 6.139e6/s²,
// c = 0.15·√(2k) = 525.6/s, drag 80/s: stable while 8k·dt² + (16c − 160)·dt < 4, up to 0.2066 ms;
// 25 Hz × 250 sub-steps is 0.16 ms.
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
    "cohesion_range = 0.4\n"                                   // 14
    "flow_mm3_per_s_per_mm = 3.2\n"                            // 15
    "bleed_s = 1.5\n"                                          // 16
    "lifetime_s = 10\n"                                        // 17
    "fade_s = 2.5\n"                                           // 18
    "gravity_mm_s2 = [-100.5, 1500]\n"                         // 19
    "drag_per_s = 80\n"                                        // 20
    "compression = 0.04\n"                                     // 21
    "damping_ratio = 0.15\n"                                   // 22
    "max_speed_mm_s = 250\n"                                   // 23
    "substeps = 250\n"                                         // 24  0.16 ms, inside the 0.2066 ms limit
    "jitter_mm = 0.02\n"                                       // 25
    "velocity_mm_s = [3, -4.5]\n"                              // 26
    "velocity_jitter_mm_s = 1.25\n"                            // 27
    "particle_volume_mm3 = 0.008\n"                            // 28
    "splat_radius_mm = 0.4\n"                                  // 29
    "clot_s = 3.0\n"                                           // 30
    "design_depth_mm = 10\n"                                   // 31
    "cohesion_mm3_s2 = 40\n"                                   // 32
    "pinning_mm3_s2 = 12.5\n"                                  // 33
    "yield_mm2_s2 = 7\n"                                       // 34
    "birth_s = 0.05\n"                                         // 35
    "[[cut]]\n"                                                // 36  its wound's flow from [particles]
    "x_mm = 8.0\n"                                             // 37
    "y_mm = 2.0\n"                                             // 38
    "\n"                                                       // 39
    "[[cut]]\n"                                                // 40  its own
    "x_mm = 4.0\n"                                             // 41
    "y_mm = 3.0\n"                                             // 42
    "start_s = 0.5\n"                                          // 43
    "wound_mm = 2.5\n"                                         // 44
    "flow_mm3_per_s_per_mm = 9.6\n"                            // 45
    "bleed_s = 0.25\n"                                         // 46
    "clot_s = 0\n"                                             // 47
    "[output]\n"                                               // 48
    "fields = [\"splat/thickness\", \"particles/position\"]\n";  // 49

TEST(ScenarioParticles, ReadsEveryParticleKey) {
  const Scenario scenario = parse_scenario(kFullParticles, kPath);
  const Scene& scene = scenario.scene;
  ASSERT_TRUE(scene.effects.has<ParticleParams>());
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  EXPECT_EQ(p.capacity, 4096);
  EXPECT_EQ(p.diameter_mm, 0.25);
  EXPECT_EQ(p.cell_mm, 0.5);
  EXPECT_EQ(p.cohesion_range, 0.4);
  EXPECT_EQ(p.flow_mm3_per_s_per_mm, 3.2);
  EXPECT_EQ(p.bleed_s, 1.5);
  EXPECT_EQ(p.lifetime_s, 10.0);
  EXPECT_EQ(p.fade_s, 2.5);
  EXPECT_EQ(p.gravity_x_mm_s2, -100.5);
  EXPECT_EQ(p.gravity_y_mm_s2, 1500.0);
  EXPECT_EQ(p.drag_per_s, 80.0);
  EXPECT_EQ(p.compression, 0.04);
  EXPECT_EQ(p.damping_ratio, 0.15);
  EXPECT_EQ(p.max_speed_mm_s, 250.0);
  EXPECT_EQ(p.substeps, 250);
  EXPECT_EQ(p.jitter_mm, 0.02);
  EXPECT_EQ(p.velocity_x_mm_s, 3.0);
  EXPECT_EQ(p.velocity_y_mm_s, -4.5);
  EXPECT_EQ(p.velocity_jitter_mm_s, 1.25);
  EXPECT_EQ(p.particle_volume_mm3, 0.008);
  EXPECT_EQ(p.splat_radius_mm, 0.4);
  EXPECT_EQ(p.clot_s, 3.0);
  EXPECT_EQ(p.design_depth_mm, 10.0);
  EXPECT_EQ(p.cohesion_mm3_s2, 40.0);
  EXPECT_EQ(p.pinning_mm3_s2, 12.5);
  EXPECT_EQ(p.yield_mm2_s2, 7.0);
  EXPECT_EQ(p.birth_s, 0.05);
  EXPECT_FALSE(scene.effects.has<SpreadParams>());  // [particles] declares the particle flow alone

  ASSERT_EQ(scene.cuts.size(), 2u);
  EXPECT_EQ(scene.cuts[0].wound_mm, 1.0);               // a cut stands for 1 mm of wound unless it says
  EXPECT_EQ(scene.cuts[0].flow_mm3_per_s_per_mm, 3.2);  // from [particles]
  EXPECT_EQ(scene.cuts[0].bleed_s, 1.5);                // from [particles]
  EXPECT_EQ(scene.cuts[0].clot_s, 3.0);                 // from [particles]
  EXPECT_EQ(scene.cuts[1].start_s, 0.5);
  EXPECT_EQ(scene.cuts[1].wound_mm, 2.5);
  EXPECT_EQ(scene.cuts[1].flow_mm3_per_s_per_mm, 9.6);
  EXPECT_EQ(scene.cuts[1].bleed_s, 0.25);
  EXPECT_EQ(scene.cuts[1].clot_s, 0.0);

  EXPECT_EQ(scenario.output.fields, (std::vector<std::string>{"splat/thickness", "particles/position"}));

  EXPECT_EQ(scenario.place_of("particles").line, 10);
  EXPECT_EQ(scenario.place_of("particles.capacity").line, 11);
  EXPECT_EQ(scenario.place_of("particles.gravity_mm_s2").line, 19);
  EXPECT_EQ(scenario.place_of("particles.max_speed_mm_s").line, 23);
  EXPECT_EQ(scenario.place_of("particles.substeps").line, 24);
  EXPECT_EQ(scenario.place_of("particles.particle_volume_mm3").line, 28);
  EXPECT_EQ(scenario.place_of("particles.birth_s").line, 35);
  EXPECT_EQ(scenario.place_of("cut[1].flow_mm3_per_s_per_mm").line, 45);
}

TEST(ScenarioParticles, AnEmptyTableTakesTheTablesDefaults) {
  const Scenario scenario = parse_scenario(kParticleBase, kPath);
  ASSERT_TRUE(scenario.scene.effects.has<ParticleParams>());
  const ParticleParams& p = scenario.scene.effects.get<ParticleParams>();
  const ParticleParams defaults;
  // Every member the table names holds the struct's own default (what `bleedsim params` shows).
  int compared = 0;
  for (const Param<ParticleParams>& param : particle_table().params)
    std::visit(
        [&](auto field) {
          using F = decltype(field);
          if constexpr (std::is_same_v<F, VectorRef (*)(ParticleParams&)>) {
            EXPECT_EQ(field(const_cast<ParticleParams&>(p)).x, field(const_cast<ParticleParams&>(defaults)).x);
            EXPECT_EQ(field(const_cast<ParticleParams&>(p)).y, field(const_cast<ParticleParams&>(defaults)).y);
            ++compared;
          } else if constexpr (!std::is_same_v<F, std::monostate>) {
            EXPECT_EQ(field(const_cast<ParticleParams&>(p)), field(const_cast<ParticleParams&>(defaults))) << param.key;
            ++compared;
          }
        },
        param.field);
  EXPECT_EQ(compared, int(particle_table().params.size()));
  // A cut that gives no flow of its own takes [particles]' defaults.
  ASSERT_EQ(scenario.scene.cuts.size(), 1u);
  EXPECT_EQ(scenario.scene.cuts[0].flow_mm3_per_s_per_mm, defaults.flow_mm3_per_s_per_mm);
  EXPECT_EQ(scenario.scene.cuts[0].bleed_s, defaults.bleed_s);
  EXPECT_TRUE(scenario.output.fields.empty());
}

TEST(ScenarioParticles, FadeDefaultsToTheLifetimeWhenTheLifetimeIsShorter) {
  const Scenario scenario = parse_scenario(particles_with("lifetime_s = 0.5\n"), kPath);
  const Scene& scene = scenario.scene;
  EXPECT_EQ(scene.effects.get<ParticleParams>().lifetime_s, 0.5);
  EXPECT_EQ(scene.effects.get<ParticleParams>().fade_s, 0.5);
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
      {"cell_mm = 0.1", "particles.cell_mm",
       "must be 0 (the range) or at least the range, diameter_mm × (1 + cohesion_range) = 0.26 mm (got 0.1)"},
      {"flow_mm3_per_s_per_mm = -5", "particles.flow_mm3_per_s_per_mm", "must be between 0 and 1e+06 (got -5)"},
      {"particle_volume_mm3 = 0", "particles.particle_volume_mm3",
       "must be greater than 0 and at most 1e+06 (got 0)"},
      {"particle_volume_mm3 = 2e6", "particles.particle_volume_mm3",
       "must be greater than 0 and at most 1e+06 (got 2e+06)"},
      {"bleed_s = -1", "particles.bleed_s", "must be between 0 and 86400 (got -1)"},
      {"clot_s = -1", "particles.clot_s", "must be between 0 and 86400 (got -1)"},
      {"lifetime_s = 0", "particles.lifetime_s", "must be greater than 0 and at most 86400 (got 0)"},
      {"lifetime_s = nan", "particles.lifetime_s", "must be a finite number (got nan)"},
      {"fade_s = 0", "particles.fade_s", "must be greater than 0 and at most 86400 (got 0)"},
      // 30: the default lifetime.
      {"fade_s = 30.5", "particles.fade_s", "must be at most lifetime_s, 30 s (got 30.5)"},
      {"drag_per_s = -1", "particles.drag_per_s", "must be between 0 and 1e+06 (got -1)"},
      {"compression = 0", "particles.compression", "must be greater than 0 and at most 0.5 (got 0)"},
      {"design_depth_mm = -1", "particles.design_depth_mm", "must be between 0 and 10000 (got -1)"},
      {"damping_ratio = 1.5", "particles.damping_ratio", "must be between 0 and 1 (got 1.5)"},
      {"cohesion_mm3_s2 = -1", "particles.cohesion_mm3_s2", "must be between 0 and 1e+06 (got -1)"},
      {"cohesion_range = 3", "particles.cohesion_range", "must be between 0 and 2 (got 3)"},
      {"pinning_mm3_s2 = -1", "particles.pinning_mm3_s2", "must be between 0 and 1e+06 (got -1)"},
      {"yield_mm2_s2 = -1", "particles.yield_mm2_s2", "must be between 0 and 1e+06 (got -1)"},
      {"birth_s = 11", "particles.birth_s", "must be between 0 and 10 (got 11)"},
      {"max_speed_mm_s = 0", "particles.max_speed_mm_s", "must be greater than 0 and at most 100000 (got 0)"},
      {"max_speed_mm_s = 2e5", "particles.max_speed_mm_s", "must be greater than 0 and at most 100000 (got 200000)"},
      {"substeps = -1", "particles.substeps", "must be between 0 and 100000 (got -1)"},
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
  EXPECT_EQ(
      parse_scenario(particles_with("lifetime_s = 5\nfade_s = 5\n"), kPath).scene.effects.get<ParticleParams>().fade_s,
      5.0);
}

TEST(ScenarioParticles, CellSmallerThanTheRange) {
  // Range: 0.5 × (1 + 0.3) = 0.65 mm.
  EXPECT_TRUE(refused_at(particles_with("diameter_mm = 0.5\ncell_mm = 0.6\n"), kParticlesEnd + 1, "particles.cell_mm",
                         "must be 0 (the range) or at least the range, diameter_mm × (1 + cohesion_range) = 0.65 mm "
                         "(got 0.6)"));
  // A cell as large as the range is the smallest allowed.
  EXPECT_EQ(parse_scenario(particles_with("diameter_mm = 0.5\ncell_mm = 0.65\n"), kPath)
                .scene.effects.get<ParticleParams>()
                .cell_mm,
            0.65);
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

// The contact's stability limit and the fewest sub-steps inside it, derived here from the formulas
// of docs/particles.md for the defaults on kParticleBase's 16 × 12 mm panel at 30 Hz:
// H = min(12, 2·√(16384 · (√3/2)·0.04 / π)) = min(12, 26.9) = 12 mm (the panel, not the ring's
// quarter-disc), a_coh = 20·0.2/0.004 = 1000 mm/s², k = (1000·12 + 1000·0.2)/(0.02·0.04) = 1.525e7,
// c = 0.1·√(2k) = 552.3, γ = 100.
struct Limit {
  double dt_s;
  int fewest;
};
Limit default_limit(double frame_rate_hz) {
  const double k = (1000.0 * 12.0 + 1000.0 * 0.2) / (0.02 * 0.04), c = 0.1 * std::sqrt(2.0 * k), drag = 100.0;
  const double a = 8.0 * k, b = 16.0 * c - 2.0 * drag;
  const double limit = (-b + std::sqrt(b * b + 16.0 * a)) / (2.0 * a);
  int fewest = 1;
  while (1.0 / (frame_rate_hz * fewest) >= limit) ++fewest;
  return {limit, fewest};
}

TEST(ScenarioParticles, SubStepsPastTheStabilityLimitAreRefusedWithTheFewestInsideIt) {
  const Limit limit = default_limit(30.0);
  ASSERT_GT(limit.fewest, 10);
  const std::string too_few = particles_with("substeps = " + std::to_string(limit.fewest - 1) + "\n");
  EXPECT_TRUE(refused_at(too_few, kParticlesEnd, "particles.substeps",
                         "use at least " + std::to_string(limit.fewest) + " sub-steps per frame"));
  // The fewest inside the limit are accepted, and substeps = 0 (the default) takes them.
  const std::string fewest = particles_with("substeps = " + std::to_string(limit.fewest) + "\n");
  EXPECT_EQ(parse_scenario(fewest, kPath).scene.effects.get<ParticleParams>().substeps, limit.fewest);
  const Scene scene = parse_scenario(kParticleBase, kPath).scene;
  EXPECT_EQ(resolve_particles(scene.effects.get<ParticleParams>(), scene).mechanics.substeps, limit.fewest);
  EXPECT_NEAR(resolve_particles(scene.effects.get<ParticleParams>(), scene).mechanics.step_limit_s, limit.dt_s, 1e-12);
}

// A film with depth (docs/particles.md#a-film-with-depth): gravity into the mucosa defaults to what
// Earth's leaves after the panel's, √(9810² − 1000²) = 9758.9 mm/s², and cohesion to none.
TEST(ScenarioParticles, AFilmWithDepthTakesItsNormalGravityFromEarthsAndNoCohesion) {
  const Scene scene = parse_scenario(particles_with("film_depth = true\n"), kPath).scene;
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  EXPECT_TRUE(p.film_depth);
  EXPECT_EQ(p.cohesion_mm3_s2, 0.0);
  EXPECT_NEAR(normal_gravity_mm_s2(p), std::sqrt(9810.0 * 9810.0 - 1000.0 * 1000.0), 1e-9);
  const ParticleSettings s = resolve_particles(scene);
  EXPECT_TRUE(has_depth(s.model));
  EXPECT_EQ(s.model.stiffness, 0.0f);
  EXPECT_EQ(s.model.cohesion, 0.0f);
  // A parcel reaches the panel's edge: its walls are the edges themselves.
  EXPECT_EQ(s.model.min_x, 0.0f);
  EXPECT_EQ(s.model.max_y, 12.0f);
}

TEST(ScenarioParticles, AFilmWithDepthNeedsGravityIntoTheMucosa) {
  // Not written, it is blamed at its table's line.
  EXPECT_TRUE(refused_at(particles_with("film_depth = true\ngravity_mm_s2 = [0, 9810]\n"), kParticlesEnd - 1,
                         "particles.gravity_normal_mm_s2",
                         "a film with depth needs gravity into the mucosa, and with gravity_mm_s2 = [0, 9810] "
                         "Earth's leaves none"));
  // Given, it is what it says.
  const Scene given =
      parse_scenario(particles_with("film_depth = true\ngravity_mm_s2 = [0, 9810]\ngravity_normal_mm_s2 = 500\n"),
                     kPath)
          .scene;
  EXPECT_EQ(normal_gravity_mm_s2(given.effects.get<ParticleParams>()), 500.0);
}

// A film with depth's contact line is measured on a grid fitted to the panel (core/physics/
// particle_line.h): 16 / 0.52 = 30.8 squares across, so 31 of 16/31 mm; 12 / 0.52 = 23.1 down, so 23 of
// 12/23 mm. A grid finer than a parcel would leave dry nodes inside the film, and is refused at its key.
TEST(ScenarioParticles, AFilmWithDepthsContactLineGridFitsThePanelAndNoFinerThanAParcel) {
  const ParticleModel m = resolve_particles(parse_scenario(particles_with("film_depth = true\n"), kPath).scene).model;
  EXPECT_EQ(m.line_nodes_x, 32);
  EXPECT_EQ(m.line_nodes_y, 24);
  EXPECT_FLOAT_EQ(m.line_step_x, float(16.0 / 31.0));
  EXPECT_FLOAT_EQ(m.line_step_y, float(12.0 / 23.0));
  // A node is wet at 0.01 mm: that depth over a square is this much of a parcel's 0.004 mm³.
  EXPECT_FLOAT_EQ(m.wetted_weight, float(0.01 * (16.0 / 31.0) * (12.0 / 23.0) / 0.004));
  EXPECT_TRUE(refused_at(particles_with("film_depth = true\nline_grid_mm = 0.1\n"), kParticlesEnd + 1,
                         "particles.line_grid_mm", "must be at least diameter_mm, 0.2 mm, once fitted to the panel: "));
  EXPECT_TRUE(refused_at(particles_with("film_depth = true\nline_grid_mm = 0\n"), kParticlesEnd + 1,
                         "particles.line_grid_mm", "must be greater than 0"));
}

// A film with depth's step follows its fastest wave and the speed limit; a sub-step past the waves'
// limit is refused with what sets it. On the 16 × 12 mm panel the ring's 65.5 mm³ pools 0.916 mm deep
// against the floor (a wedge √(2·65.5·0.1025/16) deep, 8.9 mm long: the 12 mm panel holds it), and
// ω = √(10.18·9759·0.916)/0.52 = 580/s: stable up to 3.76 ms with the drag, so 5 sub-steps of
// 6.67 ms are past it.
TEST(ScenarioParticles, AFilmWithDepthsStepIsRefusedPastItsWavesLimit) {
  EXPECT_TRUE(refused_at(particles_with("film_depth = true\nsubsteps = 5\n"), kParticlesEnd + 1, "particles.substeps",
                         "a sub-step of 6.667 ms is past the film's waves' stability limit of "));
  const Scene scene = parse_scenario(particles_with("film_depth = true\n"), kPath).scene;
  const ParticleMechanics m = resolve_particles(scene).mechanics;
  EXPECT_NEAR(m.depth_mm, std::sqrt(2.0 * 16384 * 0.004 * (1000.0 / 9758.9) / 16.0), 1e-3);
  EXPECT_NEAR(std::sqrt(m.wave_per_s2), std::sqrt(10.18 * 9758.9 * m.depth_mm) / 0.52, 1e-6 * std::sqrt(m.wave_per_s2));
  // The fewest: the speed limit's, 100 mm/s × dt under 0.1 mm, dt < 1 ms: 34 at 30 Hz.
  EXPECT_EQ(m.substeps, 34);
}

TEST(ScenarioParticles, AFilmWithDepthHasNoCohesion) {
  EXPECT_TRUE(refused_at(particles_with("film_depth = true\ncohesion_mm3_s2 = 5\n"), kParticlesEnd + 1,
                         "particles.cohesion_mm3_s2", "a film with depth has no cohesion between its parcels (got 5)"));
}

TEST(ScenarioParticles, AFilmWithDepthRunsOnTheFlatPanelOnly) {
  const std::string turbinate = (fs::path(source_dir()) / "scenarios" / "turbinate.toml").string();
  try {
    load_scenario(turbinate, ReadTissue::draw, {"particles.film_depth = true"});
    ADD_FAILURE() << "a film with depth on the turbinate's mesh was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("particles.film_depth: a film with depth runs on the flat panel only, not on a tissue.mesh"),
              std::string::npos)
        << e.what();
  }
}

TEST(ScenarioParticles, TheSpeedLimitMustKeepAStepUnderHalfADiameter) {
  // 1e5 mm/s × 1/(30·fewest) s is far over 0.1 mm.
  EXPECT_TRUE(refused_at(particles_with("max_speed_mm_s = 1e5\n"), kParticlesEnd, "particles.max_speed_mm_s",
                         "mm a sub-step, not less than half a diameter (0.1 mm)"));
}

TEST(ScenarioParticles, EmissionPastTheSpeedLimitIsRefused) {
  // |(0, 95)| + √2·5 = 102.07 mm/s, past the default 100.
  EXPECT_TRUE(refused_at(particles_with("velocity_mm_s = [0, 95]\n"), kParticlesEnd, "particles.velocity_mm_s",
                         "a new particle may leave at up to 102.1 mm/s (|velocity_mm_s| + √2 × velocity_jitter_mm_s), "
                         "past max_speed_mm_s = 100"));
  EXPECT_NO_THROW(parse_scenario(particles_with("velocity_mm_s = [0, 90]\n"), kPath));
}

TEST(ScenarioParticles, AFilmThickerThanTheSplatCanSumIsRefused) {
  // 100 mm³ in one 0.25 × 0.25 mm pixel (a splat that reaches no pixel centre puts it all there):
  // 1600 mm, past the 1e9 units of 2⁻²⁴ mm (59.6 mm) one deposit may hold.
  EXPECT_TRUE(refused_at(particles_with("particle_volume_mm3 = 100\n"), kParticlesEnd,
                         "particles.particle_volume_mm3",
                         "a particle of 100 mm³ in one pixel of 0.0625 mm² is 1600 mm thick; the splat holds at most "
                         "59.6 mm per particle in a pixel"));
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

TEST(ScenarioParticles, CollisionGridOfTheRangeTooLargeNamesTheDiameter) {
  // A 10 m panel in cells of the range, 0.12·1.3 = 0.156 mm: ⌈64102.6⌉² = 4.109e9 cells. cell_mm
  // is not written, so the diameter set the cells.
  const std::string huge = with_line(with_line(particles_with("diameter_mm = 0.12\n"), 4, "width_mm = 10000"), 5,
                                     "height_mm = 10000");
  EXPECT_TRUE(refused_at(huge, kParticlesEnd, "particles.diameter_mm",
                         "the collision grid would have 4.109e+09 cells of 0.156 mm; at most 4e9"));
  EXPECT_TRUE(refused_at(with_line(huge, kParticlesEnd, "diameter_mm = 0.12\ncell_mm = 0.156"), kParticlesEnd + 1,
                         "particles.cell_mm", "the collision grid would have 4.109e+09 cells of 0.156 mm; at most 4e9"));
}

// Issue 13: a nanometre particle on a 16 x 12 mm panel needs ~1e20 grid cells and more sub-steps
// than an int holds. Both counts are checked before anything narrows them (a cast of either to
// int is undefined, and UBSan's float-cast-overflow stops the sanitizer build on it), and the
// refusal names the diameter, which set them.
TEST(ScenarioParticles, ATinyDiameterIsRefusedAtItsKeyBeforeAnyCountOverflows) {
  // The range is 1e-9·1.3 mm: ⌈16 / 1.3e-9⌉ · ⌈12 / 1.3e-9⌉ = 1.136e20 cells, past 2^64.
  EXPECT_TRUE(refused_at(particles_with("diameter_mm = 1e-9\nsplat_radius_mm = 1.0\n"), kParticlesEnd,
                         "particles.diameter_mm", "the collision grid would have 1.136e+20 cells"));
  // With cells large enough for the grid, the contact's stiffness (∝ 1/d²) asks for ~1e13 sub-steps.
  EXPECT_TRUE(refused_at(particles_with("diameter_mm = 1e-6\ncell_mm = 1.0\n"), kParticlesEnd,
                         "particles.diameter_mm", "needs more than 100000 sub-steps per frame"));
}

TEST(ScenarioParticles, UnknownKeySuggestsTheNearest) {
  EXPECT_TRUE(refused_at(particles_with("compresion = 0.02\n"), kParticlesEnd, "particles.compresion",
                         "unknown key; did you mean 'compression'?"));
  EXPECT_TRUE(refused_at(particles_with("gravity = [0, 9.8]\n"), kParticlesEnd, "particles.gravity",
                         "unknown key (known here: capacity diameter_mm particle_volume_mm3"));
}

TEST(ScenarioParticles, CutWoundFlowAndBleedOverrideTheTablesDefaults) {
  const Scenario scenario = parse_scenario(particles_with("flow_mm3_per_s_per_mm = 1.2\nbleed_s = 4\n") +
                                               "[[cut]]\nx_mm = 1.0\ny_mm = 1.0\nflow_mm3_per_s_per_mm = 0\n"
                                               "[[cut]]\nx_mm = 2.0\ny_mm = 2.0\nbleed_s = 0.5\nwound_mm = 3\n",
                                           kPath);
  const Scene& scene = scenario.scene;
  ASSERT_EQ(scene.cuts.size(), 3u);
  EXPECT_EQ(scene.cuts[0].flow_mm3_per_s_per_mm, 1.2);  // from [particles]
  EXPECT_EQ(scene.cuts[0].bleed_s, 4.0);
  EXPECT_EQ(scene.cuts[1].flow_mm3_per_s_per_mm, 0.0);  // a cut that does not bleed particles
  EXPECT_EQ(scene.cuts[1].bleed_s, 4.0);
  EXPECT_EQ(scene.cuts[2].flow_mm3_per_s_per_mm, 1.2);
  EXPECT_EQ(scene.cuts[2].bleed_s, 0.5);
  EXPECT_EQ(scene.cuts[2].wound_mm, 3.0);
}

TEST(ScenarioParticles, CutFlowOrBleedOutOfRange) {
  // The new [[cut]] starts on kParticlesEnd.
  EXPECT_TRUE(refused_at(particles_with("[[cut]]\nx_mm = 1.0\ny_mm = 1.0\nflow_mm3_per_s_per_mm = -1\n"),
                         kParticlesEnd + 3, "cut[1].flow_mm3_per_s_per_mm", "must be between 0 and 1e+06 (got -1)"));
  EXPECT_TRUE(refused_at(particles_with("[[cut]]\nx_mm = 1.0\ny_mm = 1.0\nbleed_s = -0.5\n"), kParticlesEnd + 3,
                         "cut[1].bleed_s", "must be between 0 and 86400 (got -0.5)"));
  // 1e6 mm³/s/mm × 1 mm of 0.004 mm³ particles: 2.5e8 a second, past the 1e8 allowed.
  EXPECT_TRUE(refused_at(particles_with("[[cut]]\nx_mm = 1.0\ny_mm = 1.0\nflow_mm3_per_s_per_mm = 1e6\n"),
                         kParticlesEnd + 3, "cut[1].flow_mm3_per_s_per_mm", "gives 2.5e+08 particles per second"));
}

TEST(ScenarioParticles, CutFlowKeysWithoutParticlesAreRefusedAtTheirLine) {
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "flow_mm3_per_s_per_mm = 1"), 16, "cut[1].flow_mm3_per_s_per_mm",
                         "has no effect: this scene declares no [particles]"));
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "bleed_s = 1.0"), 16, "cut[1].bleed_s",
                         "has no effect: this scene declares no [particles]"));
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "wound_mm = 2"), 16, "cut[1].wound_mm",
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

}  // namespace
}  // namespace bleedsim