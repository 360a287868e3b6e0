// The force's quality contact by contact (core/haptics/contact_quality.h) on synthetic motions played
// through the haptic loop itself: a ramp into the spring (penetration, rise time and overshoot known
// exactly), a step in and out (its rate), contacts cut where the tip leaves, and a run that ends in
// contact. Each bound is derived beside its assertion.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/haptics/contact_quality.h"
#include "core/haptics/haptics.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The in-code 16 × 12 mm panel with the stylus over its centre: surface z = 120 mm, k and b as given.
Scene scene_with(double k, double b) {
  Scene scene = test::scene_in_code(true);
  HapticParams h;
  h.origin_x_mm = 8.0;
  h.origin_y_mm = 6.0;
  h.stiffness_N_per_m = k;
  h.damping_Ns_per_m = b;
  scene.haptics = h;
  return scene;
}

// The tip's height z (mm) at each tick, straight over the panel's centre, through the loop and the meter.
ContactQualityMeter measured(const Scene& scene, const std::vector<double>& z_mm, bool finish = true) {
  HapticLoop loop(scene);
  ContactQualityMeter meter(*scene.haptics);
  for (double z : z_mm) meter.add(loop.tick(DeviceSample{Eigen::Vector3d(0, 0, z / 1000.0), 0}).record);
  if (finish) meter.finish();
  return meter;
}

TEST(ContactQuality, ARampIntoTheSpringRisesInFourFifthsOfItsPeakOverTheSlope) {
  // The tip comes down at v = 10 mm/s (0.01 mm a tick) from z = 121.005 mm for 300 ticks, holds 100
  // ticks at 118.005 mm, goes back up at v for 300 ticks. It crosses the surface half way between ticks
  // 100 and 101 going in, and 599 and 600 coming out: contact from tick 101 to 599 (z_599 = 119.995).
  // Going in, F_n = k·p_n + b·v with p_n = v·T·(n − 100.5): a line of slope k·v·T = 5 mN a tick,
  // F_n = 0.005·(n − 99.5) N, up to tick 300; holding, k·D with D = 1.995 mm; so the peak is tick 300's
  // F = k·D + b·v = 0.9975 + 0.005 = 1.0025 N. Both crossings fall on the line (10 %: n = 119.55,
  // 90 %: n = 279.95), so the rise is 0.8·F_pk / (k·v) = 0.8·(D/v + b/k) = 0.1604 s. The force exceeds
  // the spring by b·v = 5 mN while pressing (0 holding; less coming out): the overshoot.
  const double k = 500, b = 0.5, v = 0.01;  // N/m, N·s/m, m/s
  std::vector<double> z;
  for (int n = 0; n <= 300; ++n) z.push_back(121.005 - 0.01 * n);
  z.insert(z.end(), 100, z.back());
  for (int n = 1; n <= 300; ++n) z.push_back(118.005 + 0.01 * n);
  const ContactQualityMeter meter = measured(scene_with(k, b), z);
  ASSERT_EQ(meter.contacts().size(), 1u);
  const ContactQuality& c = meter.contacts()[0];
  EXPECT_EQ(c.first_tick, 101);
  EXPECT_EQ(c.last_tick, 599);
  EXPECT_TRUE(c.released);
  // Rounding: each z (mm) is within ε·121 mm of its value and within ε more in metres: p within
  // 6e-17 m, k·p within 3e-14 N; v_n = Δz/T within 5.4e-14 m/s, b·v_n within 2.7e-14 N. So each F
  // is within δF = 6e-14 N (+ ε·F). A crossing moves by at most (|δlevel| + 2·δF) / (5 mN a tick),
  // under 4e-11 ticks; the rise by twice that, 8e-14 s: 1e-12 s is a bound with room.
  const double depth_m = 0.001995;
  EXPECT_NEAR(c.max_penetration_m, depth_m, 1e-16);   // p within 6e-17 m, as above
  EXPECT_NEAR(c.peak_force_N, k * depth_m + b * v, 1e-13);
  ASSERT_TRUE(c.rise_time_s.available()) << c.rise_time_s.unavailable;
  EXPECT_NEAR(c.rise_time_s.value, 0.8 * (depth_m / v + b / k), 1e-12);
  EXPECT_NEAR(c.overshoot_N, b * v, 1e-13);
  EXPECT_EQ(c.ticks_at_force_limit, 0);
  // Passive settings (k·T/2 + b = 0.75 < B = 1.5): Colgate & Schenkel's bound holds for any motion,
  // so D − W ≥ 0 over the contact (here by far: it is the damper's and the device's dissipation).
  EXPECT_GT(c.margin_end_J, 0.0);
  // The per-tick margin is the contact's, and zero out of it.
  EXPECT_EQ(meter.margin_J()[100], 0.0);
  EXPECT_EQ(meter.margin_J()[599], c.margin_end_J);
  EXPECT_EQ(meter.margin_J()[600], 0.0);
}

TEST(ContactQuality, AStepInAndOutIsItsForceOverOneTickAndRisesWithinATick) {
  // b = 0: the tip jumps from 121 mm to 118 mm (2 mm in: F = k·0.002 = 1 N) for 50 ticks, then out. The
  // rates: 1 N/T = 1000 N/s in and out, 0 between: p50 0, max 1000 N/s. F is within 500·5.3e-17 N of
  // 1 N (p = 0.120 − 0.118 from two rounded quotients), so the rates within 2.7e-11 N/s (+ ε·1000).
  std::vector<double> z(10, 121.0);
  z.insert(z.end(), 50, 118.0);
  z.insert(z.end(), 10, 121.0);
  const ContactQualityMeter meter = measured(scene_with(500, 0), z);
  ASSERT_EQ(meter.contacts().size(), 1u);
  const ContactQuality& c = meter.contacts()[0];
  EXPECT_EQ(c.ticks(), 50);
  EXPECT_EQ(c.force_rate.p50_N_per_s, 0.0);
  EXPECT_NEAR(c.force_rate.max_N_per_s, 1000.0, 5e-11);
  EXPECT_EQ(c.rise_time_s.unavailable, "the force peaks on the contact's first tick: it rises within one tick");
  // 50 ticks: at least one cutoff period (34); the force is constant: nothing above 30 Hz, no share.
  EXPECT_EQ(c.oscillation.rms_above_N.value, 0.0);
  EXPECT_FALSE(c.oscillation.share_above.available());
}

TEST(ContactQuality, ContactsAreCutWhereTheTipLeavesAndAShortOneSaysWhatItLacks) {
  // In for 1 tick, out for 3, in for 20, out, in for 40 and the run ends there.
  std::vector<double> z{121.0, 119.0, 121.0, 121.0, 121.0};
  z.insert(z.end(), 20, 119.0);
  z.push_back(121.0);
  z.insert(z.end(), 40, 119.0);
  const ContactQualityMeter meter = measured(scene_with(500, 0.5), z);
  ASSERT_EQ(meter.contacts().size(), 3u);
  const ContactQuality& one = meter.contacts()[0];
  EXPECT_EQ(one.first_tick, 1);
  EXPECT_EQ(one.last_tick, 1);
  EXPECT_EQ(one.rise_time_s.unavailable, "a contact of 1 tick: the force has no rise to measure");
  EXPECT_NE(one.oscillation.rms_above_N.unavailable.find("a contact of 1 tick is shorter than one period"),
            std::string::npos);
  EXPECT_EQ(meter.contacts()[1].first_tick, 5);
  EXPECT_EQ(meter.contacts()[1].last_tick, 24);
  EXPECT_NE(meter.contacts()[1].oscillation.rms_above_N.unavailable.find("a contact of 20 ticks"), std::string::npos);
  const ContactQuality& open = meter.contacts()[2];
  EXPECT_EQ(open.first_tick, 26);
  EXPECT_EQ(open.last_tick, 65);
  EXPECT_FALSE(open.released);
  EXPECT_TRUE(open.oscillation.rms_above_N.available());
  // Its last tick's hold is not known: the margin stops at the hold before.
  EXPECT_EQ(meter.margin_J()[65], meter.margin_J()[64]);
}

TEST(ContactQuality, TicksMustFollowOneAnother) {
  Scene scene = scene_with(500, 0.5);
  ContactQualityMeter meter(*scene.haptics);
  HapticTick tick;
  tick.tick = 1;
  EXPECT_THROW(meter.add(tick), std::invalid_argument);
}

}  // namespace
}  // namespace bleedsim
