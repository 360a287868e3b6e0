// The Z-width at 1 kHz (docs/haptics.md, "Z-width"): the edge Colgate & Schenkel's bound draws in the
// stiffness–damping plane, b_max(k) = B − k·T/2, and every shipped scenario's contact placed inside it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/haptics/haptic_params.h"
#include "core/io/scenario.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

TEST(ZWidth, TheEdgeIsTheDevicesDampingLessHalfTheSpringTimesThePeriod) {
  // B = 1.5 N·s/m, T = 1 ms: b_max(0) = B; b_max(500) = 1.5 − 0.25 = 1.25; b_max(3000) = 0, CHAI3D's
  // Falcon limit (docs/haptics.md); beyond it no damping is passive. Each is one product and one
  // difference of numbers near 1: within 2ε of 1.5.
  const double eps2 = 2 * 1.5 * 2.3e-16;
  EXPECT_NEAR(passive_damping_limit_Ns_per_m(0, 1.5), 1.5, eps2);
  EXPECT_NEAR(passive_damping_limit_Ns_per_m(500, 1.5), 1.25, eps2);
  EXPECT_NEAR(passive_damping_limit_Ns_per_m(3000, 1.5), 0.0, eps2);
  EXPECT_LT(passive_damping_limit_Ns_per_m(3200, 1.5), 0.0);
}

TEST(ZWidth, InsideTheEdgeIsWhatTheLoadCheckAccepts) {
  // The scenario check (passivity_problem) and the edge are the same bound: across the plane, a
  // setting passes exactly when |b| < b_max(k). The grid avoids the edge itself by 1/8 of a step.
  for (double k = 0; k <= 3200; k += 100)
    for (double b = 0.0125; b <= 2; b += 0.1) {
      HapticParams h;
      h.stiffness_N_per_m = k;
      h.damping_Ns_per_m = b;
      EXPECT_EQ(passivity_problem(h).key.empty(), b < passive_damping_limit_Ns_per_m(k, h.device_damping_Ns_per_m))
          << "k " << k << ", b " << b;
    }
}

TEST(ZWidth, EveryShippedStylusSitsInsideIt) {
  // Each scenario under scenarios/ with a [haptics] table, as loaded (the defaults where it writes
  // none): its damping below the edge at its stiffness, by the margin the docs' Z-width plot shows.
  int stylus_scenes = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(test::source_dir() + "/scenarios")) {
    if (entry.path().extension() != ".toml") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    if (text.str().find("[haptics]") == std::string::npos) continue;
    const Scenario file = load_scenario(entry.path().string(), ReadTissue::header_only);
    ASSERT_TRUE(file.scene.haptics) << entry.path();
    const HapticParams& h = *file.scene.haptics;
    const double edge = passive_damping_limit_Ns_per_m(h.stiffness_N_per_m, h.device_damping_Ns_per_m);
    EXPECT_LT(std::abs(h.damping_Ns_per_m), edge) << entry.path() << ": k " << h.stiffness_N_per_m;
    ++stylus_scenes;
  }
  EXPECT_GE(stylus_scenes, 6);  // falcon-stroke, falcon-suction and the four golden stylus scenes
}

}  // namespace
}  // namespace bleedsim
