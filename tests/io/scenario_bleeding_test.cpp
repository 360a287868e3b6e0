// The scenario's [pulse], [vessels], [suction], [contact] and [[tip]] tables (docs/bleeding.md): bad
// settings refused at their key, and a map PNG read as the density it draws.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/io/scenario.h"
#include "tests/io/scenario_text.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

using namespace test;

// [pulse] and [vessels] (docs/bleeding.md): each refusal names the file, the line and the key. A
// rule's key that the file left out is placed at its table's header.
TEST(ScenarioPulse, BadSettingsAreRefusedAtTheirKey) {
  EXPECT_TRUE(refused_at(kBase + "[pulse]\n", kEnd, "pulse.heart_rate_per_min",
                         "has no effect: this scene declares no [particles]"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[pulse]\nheart_rate_per_min = 0\n", kEnd + 2,
                         "pulse.heart_rate_per_min", "greater than 0"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[pulse]\nsystolic = 0.8\n", kEnd + 1, "pulse.dicrotic",
                         "systolic + dicrotic must be below 1"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[pulse]\nsystolic = 0.2\n", kEnd + 1, "pulse.dicrotic",
                         "must be below systolic"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\nvelocity_mm_s = [0, 60]\n[pulse]\n", kEnd + 2, "pulse.systolic",
                         "past particles.max_speed_mm_s"));
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "arterial = true") + "[particles]\n", 16, "cut[1].arterial",
                         "has no effect: this scene declares no [pulse]"));
}

TEST(ScenarioVessels, BadSettingsAreRefusedAtTheirKey) {
  EXPECT_TRUE(refused_at(kBase + "[vessels]\n", kEnd, "vessels.map", "has no effect: this scene declares no [particles]"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[vessels]\n[tissue]\ntexture = \"t.png\"\n", kEnd + 1, "vessels.map",
                         "this scene's tissue is a texture"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[vessels]\nmap = \"no-such-map.png\"\n", kEnd + 2, "vessels.map",
                         "no-such-map.png"));
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "wound_angle_deg = 30") + "[particles]\n", 16, "cut[1].wound_angle_deg",
                         "has no effect: this scene declares no [vessels]"));
}

// A grey map PNG is read as its grey over 255, resampled to the panel: the example's gradient,
// 48 rows rising by 255 · (j + ½)/48, on a 64 × 48 panel reads back row by row.
TEST(ScenarioVessels, AMapPngIsReadAsItsRedChannel) {
  const std::string text = kBase + "[particles]\n[vessels]\nmap = \"" + source_dir() +
                           "/scenarios/textures/vessels-gradient-64x48.png\"\n";
  const Scene scene = parse_scenario(text, kPath).scene;
  ASSERT_EQ(scene.vessel_density.size(), std::size_t(64 * 48));
  for (int j = 0; j < 48; ++j)
    EXPECT_EQ(scene.vessel_density[std::size_t(j) * 64 + 17], float(std::round(255.0 * (j + 0.5) / 48)) / 255.0f) << j;
}

// [suction], [contact] and a scripted [[tip]] path: each refusal names the file, the line and the key.
// kPathScene is kBase with [particles] (line 19) and a two-point path (lines 20 to 27).
const std::string kPathScene = kBase + "[particles]\n[[tip]]\nt_s = 0.0\nx_mm = 1.0\ny_mm = 11.0\n"
                                       "[[tip]]\nt_s = 0.5\nx_mm = 15.0\ny_mm = 11.0\n";
constexpr int kAfterPath = 28;

TEST(ScenarioSuction, BadSettingsAreRefusedAtTheirKey) {
  EXPECT_TRUE(refused_at(kBase + "[suction]\n", kEnd, "suction.radius_mm",
                         "has no effect: this scene declares no [particles]"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[suction]\n", kEnd + 1, "suction.radius_mm",
                         "has no instrument to act through"));
  EXPECT_TRUE(refused_at(kPathScene + "[suction]\nradius_mm = 0\n", kAfterPath + 1, "suction.radius_mm",
                         "greater than 0"));
  EXPECT_TRUE(refused_at(kPathScene + "[suction]\nmax_flow_mm3_per_s = -1\n", kAfterPath + 1,
                         "suction.max_flow_mm3_per_s", "between 0 and"));
  EXPECT_TRUE(refused_at(kPathScene + "[suction]\nmax_flow_mm3_per_s = 1e6\n", kAfterPath + 1,
                         "suction.max_flow_mm3_per_s", "at most 1e+08"));
  EXPECT_TRUE(refused_at(kPathScene + "[suction]\nbuttons = 16\n", kAfterPath + 1, "suction.buttons", "between 1 and 15"));
  EXPECT_TRUE(refused_at(kPathScene + "[suction]\nbuttons = 1.5\n", kAfterPath + 1, "suction.buttons",
                         "expected an integer"));
  EXPECT_TRUE(refused_at(kPathScene + "[contact]\ntip_radius_mm = 1.0\n[suction]\nradius_mm = 1.1\n", kAfterPath + 3,
                         "suction.radius_mm", "must be larger than contact.tip_radius_mm"));
}

TEST(ScenarioContact, BadSettingsAreRefusedAtTheirKey) {
  EXPECT_TRUE(refused_at(kBase + "[contact]\n", kEnd, "contact.tip_radius_mm",
                         "has no effect: this scene declares no [particles]"));
  EXPECT_TRUE(refused_at(kPathScene + "[contact]\ntip_radius_mm = 6.0\n", kAfterPath + 1, "contact.tip_radius_mm",
                         "too large for the panel"));
  EXPECT_TRUE(refused_at(kPathScene + "[contact]\ntip_radius_mm = -0.5\n", kAfterPath + 1, "contact.tip_radius_mm",
                         "greater than 0"));
}

TEST(ScenarioTip, BadPathsAreRefusedAtTheirPoint) {
  EXPECT_TRUE(refused_at(kPathScene, 20, "tip", "has no effect: a path drives [suction] or [contact]"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[[tip]]\nt_s = 0.0\nx_mm = 1.0\ny_mm = 1.0\n[suction]\n", 20, "tip",
                         "at least two points"));
  EXPECT_TRUE(refused_at(with_line(kPathScene, 25, "t_s = 0.0") + "[suction]\n", 25, "tip[1].t_s",
                         "must be later than the point before it"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[[tip]]\nx_mm = 1.0\ny_mm = 1.0\n", 20, "tip[0].t_s",
                         "missing (required)"));
  EXPECT_TRUE(refused_at(with_line(kPathScene, 26, "x_mm = nan") + "[suction]\n", 26, "tip[1].x_mm", "nan"));
  EXPECT_TRUE(refused_at(kBase + "[particles]\n[tip]\nt_s = 0.0\n", kEnd + 1, "tip", "expected [[tip]] tables"));
  const std::string trace = source_dir() + "/scenarios/traces/single-stroke.csv";
  EXPECT_TRUE(refused_at(kPathScene + "[suction]\n[haptics]\ntrace = \"" + trace + "\"\n", 20, "tip",
                         "a scene has one instrument"));
}

}  // namespace
}  // namespace bleedsim
