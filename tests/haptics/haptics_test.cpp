// The 1 kHz haptic loop (core/haptics/haptics.cpp): contact with the tissue surface, the force of a spring
// and a damper clamped to the device's maximum, the passivity bound, cuts along the path, and the
// clocks that tie ticks to frames. Expected values are worked out from the formulas in
// docs/haptics.md, not read from the code's output.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/effects/spread/spread_params.h"
#include "core/haptics/haptics.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

// The in-code scene (16 × 12 mm panel) with a stylus: surface at z = 120 mm, panel origin at its
// centre (8, 6) mm, scale 1, k = 500 N/m, b = 0.5 N·s/m, cap 8 N, cuts every 1 mm with button 0x1.
Scene haptic_scene() {
  Scene scene = test::scene_in_code(true);
  HapticParams h;
  h.origin_x_mm = 8.0;
  h.origin_y_mm = 6.0;
  scene.haptics = h;
  return scene;
}

DeviceSample at(double x_mm, double y_mm, double z_mm, std::uint8_t buttons = 0) {
  return DeviceSample{Eigen::Vector3d(x_mm, y_mm, z_mm) / 1000.0, buttons};
}

TEST(HapticPassivity, TheDefaultsArePassive) {
  // k·T/2 + |b| = 500 · 0.001 / 2 + 0.5 = 0.75 < 1.5 N·s/m.
  EXPECT_TRUE(passivity_problem(HapticParams{}).key.empty());
}

TEST(HapticPassivity, TooStiffASpringIsRefused) {
  HapticParams h;
  h.stiffness_N_per_m = 3000;  // k·T/2 = 1.5: the device's 1.5 N·s/m is used up by the spring alone
  h.damping_Ns_per_m = 0;
  const ParamProblem problem = passivity_problem(h);
  EXPECT_EQ(problem.key, "stiffness_N_per_m");
  EXPECT_NE(problem.message.find("k·T/2 + |b| = 1.5 + 0 = 1.5 N·s/m"), std::string::npos) << problem.message;
  h.stiffness_N_per_m = 2990;  // 1.495 < 1.5
  EXPECT_TRUE(passivity_problem(h).key.empty());
}

TEST(HapticPassivity, TooMuchVirtualDampingIsRefused) {
  HapticParams h;
  h.damping_Ns_per_m = 1.25;  // 0.25 + 1.25 = 1.5, not below 1.5
  EXPECT_EQ(passivity_problem(h).key, "damping_Ns_per_m");
  h.device_damping_Ns_per_m = 2.0;
  EXPECT_TRUE(passivity_problem(h).key.empty());
  EXPECT_THROW(HapticLoop(test::scene_in_code(true)), std::invalid_argument);  // no [haptics]
}

TEST(HapticContact, AboveTheSurfaceThereIsNoContactAndNoForce) {
  HapticLoop loop(haptic_scene());
  const HapticTick t = loop.tick(at(0, 0, 121.0, 0x1)).record;
  EXPECT_FALSE(t.contact);
  EXPECT_FALSE(t.cutting);
  EXPECT_EQ(t.penetration_m, 0.0);
  EXPECT_EQ(t.force_N, Eigen::Vector3d::Zero());
}

TEST(HapticContact, AStillTipFeelsTheSpringAlone) {
  HapticLoop loop(haptic_scene());
  loop.tick(at(0, 0, 118.0));
  const HapticTick t = loop.tick(at(0, 0, 118.0)).record;  // 2 mm in, not moving
  EXPECT_TRUE(t.contact);
  EXPECT_NEAR(t.penetration_m, 0.002, 1e-15);
  EXPECT_NEAR(t.force_N.z(), 500.0 * 0.002, 1e-12);  // 1 N, pushing out of the tissue (+z)
  EXPECT_EQ(t.force_N.x(), 0.0);
  EXPECT_EQ(t.force_N.y(), 0.0);
}

TEST(HapticContact, PressingInAddsDampingAndPullingOutTakesItAway) {
  HapticLoop loop(haptic_scene());
  loop.tick(at(0, 0, 118.01));
  // 0.01 mm further in over 1 ms: 10 mm/s into the tissue; the damper adds 0.5 · 0.01 = 0.005 N.
  EXPECT_NEAR(loop.tick(at(0, 0, 118.0)).record.force_N.z(), 1.0 + 0.005, 1e-9);
  // Back out at 10 mm/s: the damper takes 0.005 N from the spring's 500 · 0.00199.
  EXPECT_NEAR(loop.tick(at(0, 0, 118.01)).record.force_N.z(), 500.0 * 0.00199 - 0.005, 1e-9);
}

TEST(HapticContact, TheForceIsClampedToTheDeviceAndNeverPulls) {
  HapticLoop loop(haptic_scene());
  loop.tick(at(0, 0, 100.0));
  EXPECT_EQ(loop.tick(at(0, 0, 100.0)).record.force_N.z(), 8.0);  // k·p = 10 N, capped at 8 N
  // Leaving fast from just under the surface: the spring's 0.05 N is less than the damper's
  // 0.5 · 10 m/s: the sum is negative, and tissue cannot pull.
  loop.tick(at(0, 0, 109.9));
  const HapticTick t = loop.tick(at(0, 0, 119.9)).record;
  EXPECT_TRUE(t.contact);
  EXPECT_EQ(t.force_N.z(), 0.0);
}

TEST(HapticContact, BeyondThePanelThereIsNoTissue) {
  HapticLoop loop(haptic_scene());
  // Device x = 9 mm maps to panel x = 17 mm, past the 16 mm panel.
  const HapticTick t = loop.tick(at(9.0, 0, 110.0, 0x1)).record;
  EXPECT_NEAR(t.panel_mm.x(), 17.0, 1e-12);
  EXPECT_FALSE(t.contact);
  EXPECT_EQ(t.force_N.z(), 0.0);
}

TEST(HapticContact, DeviceYUpIsPanelYDown) {
  Scene scene = haptic_scene();
  scene.haptics->scale = 0.5;
  HapticLoop loop(scene);
  const HapticTick t = loop.tick(at(4.0, 2.0, 130.0)).record;
  EXPECT_NEAR(t.panel_mm.x(), 8.0 + 0.5 * 4.0, 1e-12);
  EXPECT_NEAR(t.panel_mm.y(), 6.0 - 0.5 * 2.0, 1e-12);
}

TEST(HapticCuts, AStrokeCutsAtOnceThenEverySpacingAlongThePath) {
  Scene scene = haptic_scene();
  scene.haptics->cut_spacing_mm = 0.9;  // clear of the 1 mm steps' rounding
  HapticLoop loop(scene);
  std::vector<Cut> cuts;
  // 0.25 mm per tick along x, 2 mm deep, button held: 41 ticks cover 10 mm, a cut every 4th.
  for (int n = 0; n <= 40; ++n)
    if (auto cut = loop.tick(at(-5.0 + 0.25 * n, 1.0, 118.0, 0x1)).cut) cuts.push_back(*cut);
  ASSERT_EQ(cuts.size(), 11u);  // at 0, 1, ..., 10 mm along
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    EXPECT_NEAR(cuts[i].x_mm, 3.0 + double(i), 1e-9);  // panel x = 8 + device x
    EXPECT_NEAR(cuts[i].y_mm, 5.0, 1e-12);             // panel y = 6 − device y
    EXPECT_DOUBLE_EQ(cuts[i].start_s, 0.004 * double(i));  // tick 4i at 4i ms
    EXPECT_EQ(cuts[i].radius_mm, scene.effects.get<SpreadParams>().radius_mm);  // the scene's wound
    EXPECT_EQ(cuts[i].growth_per_s, scene.effects.get<SpreadParams>().growth_per_s);
  }
}

TEST(HapticCuts, NoCutWithoutTheButtonOrWithoutContactAndANewStrokeCutsAtOnce) {
  HapticLoop loop(haptic_scene());
  EXPECT_FALSE(loop.tick(at(0, 0, 118.0, 0x2)).cut);  // another button: touches, does not cut
  EXPECT_FALSE(loop.tick(at(0, 0, 121.0, 0x1)).cut);  // the button, in the air
  EXPECT_TRUE(loop.tick(at(0, 0, 118.0, 0x1)).cut);   // both: the stroke's first cut
  EXPECT_FALSE(loop.tick(at(0.1, 0, 118.0, 0x1)).cut);  // 0.1 mm on: not yet
  EXPECT_FALSE(loop.tick(at(0.1, 0, 121.0, 0x1)).cut);  // lifted: the stroke ends
  EXPECT_TRUE(loop.tick(at(0.2, 0, 118.0, 0x1)).cut);   // back in: a new stroke cuts at once
}

TEST(HapticClock, TickNIsAtNMilliseconds) {
  HapticLoop loop(haptic_scene());
  for (int n = 0; n < 2500; ++n) {
    const HapticTick t = loop.tick(at(0, 0, 130.0)).record;
    ASSERT_EQ(t.tick, n);
    ASSERT_EQ(t.t_s, double(n) / 1000.0);
  }
}

TEST(HapticClock, TicksPerFrameNeverDriftFromTheIntegerCount) {
  // Through frame k (ending at (k + 1) / fps) run the ticks n ≤ (k + 1) · 1000 / fps: exactly
  // 34, 33, 34, 33, 33, 34, ... at 30 Hz, 40 a frame at 25 Hz, over a million frames (9 hours).
  Scene scene = haptic_scene();
  EXPECT_EQ(scene.haptic_ticks_through_frame(0), 34);  // ticks 0..33 ms: the frame ends at 33.3 ms
  EXPECT_EQ(scene.haptic_ticks_through_frame(2), 101);  // the frame ends at exactly 100 ms
  for (std::int64_t k = 0; k < 1'000'000; ++k)
    ASSERT_EQ(scene.haptic_ticks_through_frame(k), (k + 1) * 1000 / 30 + 1) << "frame " << k;
  scene.frame_rate_hz = 25.0;
  for (std::int64_t k = 0; k < 1'000'000; ++k) ASSERT_EQ(scene.haptic_ticks_through_frame(k), 40 * (k + 1) + 1);
}

}  // namespace
}  // namespace bleedsim