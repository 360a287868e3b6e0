// The bleeding effects' hard cases (issue 15: [suction], [contact], [pulse], [vessels]), one
// scenarios/hard/*.toml each, run on the CPU reference through the hard cases' shared checker,
// run_and_check() (tests/effects/hard_case_check.h: finite, inside the panel, the accounting exact
// with its fifth count, no particle inside a contact tip, bounded overlap, the energy's decay),
// each with its own expectations, derived in its scenario's header and beside its test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "core/bleeding/heartbeat.h"
#include "core/effects/contact/contact_params.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/pulse/pulse_params.h"
#include "core/effects/suction/suction_params.h"
#include "core/effects/vessels/vessel_params.h"
#include "core/simulation/simulation.h"
#include "tests/effects/hard_case_check.h"

namespace bleedsim {
namespace {

using test::Expect;
using test::load_hard;
using test::Particles;
using test::run_and_check;
using test::RunSummary;

// Sub-steps done by the end of the frame that shows time t (frame k shows t = (k + 1) / rate).
std::uint64_t steps_by(const Scene& scene, double t_s) {
  const ParticleMechanics mech = resolve_particles(scene.effects.get<ParticleParams>(), scene).mechanics;
  return std::uint64_t(std::llround(t_s * scene.frame_rate_hz)) * std::uint64_t(mech.substeps);
}

// ---- suction-flood -----------------------------------------------------------------------------

// The suction's quota, floor(k · x), with its rounding: k · x is computed in double (x itself a
// quotient), within a few ulps of the exact product, so floor can be one off only where k · x is
// within that of a whole number: the two floors of k · x ∓ 1e-9 bracket it (k · x < 1e5 here).
struct Quota {
  double per_step;  // x = max_flow · dt / V
  std::uint64_t least(std::uint64_t k) const {
    return std::uint64_t(std::max(0.0, std::floor(double(k) * per_step - 1e-9)));
  }
  std::uint64_t most(std::uint64_t k) const { return std::uint64_t(std::floor(double(k) * per_step + 1e-9)); }
};

TEST(BleedingHardCases, SuctionFlood) {
  Scene scene = load_hard("suction-flood");
  ASSERT_TRUE(scene.effects.has<SuctionParams>());
  ASSERT_EQ(scene.cuts.size(), 1u);
  ASSERT_EQ(scene.tips.size(), 2u);
  const ParticleParams& pp = scene.effects.get<ParticleParams>();
  const Cut& cut = scene.cuts[0];
  const TipPoint on = scene.tips.front(), off = scene.tips.back();
  const double volume = pp.particle_volume_mm3, steps_per_s = resolve_particles(scene).steps_per_s;
  const Quota quota{scene.effects.get<SuctionParams>().max_flow_mm3_per_s / steps_per_s / volume};
  // The premises of the header's closed forms: a tip held still whose reach covers the panel, a
  // flood faster than the quota, more than one particle a step, a stop at a frame's end while the
  // tip is on, and particles that outlive the ring's turn (C/E) but not the quota's drain of a
  // full ring (C/R).
  ASSERT_EQ(on.x_mm, off.x_mm);
  ASSERT_EQ(on.y_mm, off.y_mm);
  for (const double cx : {0.0, scene.domain.width_mm})
    for (const double cy : {0.0, scene.domain.height_mm})
      ASSERT_LE(std::hypot(cx - on.x_mm, cy - on.y_mm), scene.effects.get<SuctionParams>().radius_mm);
  const double flood_per_s = cut.wound_mm * cut.flow_mm3_per_s_per_mm / volume;
  ASSERT_GT(flood_per_s, scene.effects.get<SuctionParams>().max_flow_mm3_per_s / volume);
  ASSERT_GT(quota.per_step, 1.0);  // several a step: nearest first decides which
  const double stop_s = cut.start_s + cut.bleed_s;
  ASSERT_EQ(stop_s * scene.frame_rate_hz, std::round(stop_s * scene.frame_rate_hz));
  ASSERT_GT(stop_s, on.t_s);
  ASSERT_LT(stop_s, off.t_s);
  ASSERT_GT(pp.lifetime_s, pp.capacity / flood_per_s);
  ASSERT_LT(pp.lifetime_s, pp.capacity / (scene.effects.get<SuctionParams>().max_flow_mm3_per_s / volume));

  // The sub-steps with the suction on among the first n: those whose end, j / steps_per_s (as the
  // particle stage computes it), lies on the tip's path, [on.t_s, off.t_s].
  const auto sucking_steps = [&](std::uint64_t n) {
    std::uint64_t k = 0;
    for (std::uint64_t j = 1; j <= n; ++j) {
      const double t = double(j) / steps_per_s;
      k += t >= on.t_s && t <= off.t_s;
    }
    return k;
  };
  std::uint64_t alive_at_stop = 0, steps_at_stop = 0, drained_frame_quota = 0;
  double drained_at = -1.0, quota_allowed_at = -1.0;
  const auto each_frame = [&](const Particles& p) {
    const ParticleCounts& c = p.counts;
    const std::uint64_t k = sucking_steps(steps_by(scene, p.t_s));
    ASSERT_LE(c.aspirated, quota.most(k)) << "t = " << p.t_s << ", " << k << " sub-steps sucking";
    if (c.alive > 0) {
      ASSERT_GE(c.aspirated, quota.least(k)) << "t = " << p.t_s << ": the suction went short with particles in reach";
    }
    if (std::abs(p.t_s - stop_s) < 1e-9) {
      alive_at_stop = c.alive;
      steps_at_stop = k;
    }
    if (p.t_s > stop_s + 1e-9) {
      ASSERT_GT(steps_at_stop, 0u);
      // The least the quota can have allowed since the stop, rounding taken against the bound.
      const std::int64_t since = std::int64_t(quota.least(k)) - std::int64_t(quota.most(steps_at_stop));
      ASSERT_LE(std::int64_t(c.alive), std::max<std::int64_t>(0, std::int64_t(alive_at_stop) - since))
          << "t = " << p.t_s;
      if (c.alive == 0 && drained_at < 0) drained_at = p.t_s;
      if (since >= std::int64_t(alive_at_stop) && quota_allowed_at < 0) {
        quota_allowed_at = p.t_s;
        drained_frame_quota = std::uint64_t(since);
      }
    }
  };
  RunSummary r;
  run_and_check("suction-flood", scene, Expect{}, &r, each_frame);
  if (HasFatalFailure()) return;
  const ParticleCounts& c = r.final_counts;
  std::cout << "  " << alive_at_stop << " alive when the bleeding stopped at " << stop_s
            << " s; the quota since allowed " << drained_frame_quota << " by " << quota_allowed_at
            << " s; none alive from " << drained_at << " s" << std::endl;
  EXPECT_EQ(c.emitted, std::uint64_t(std::floor(flood_per_s * (stop_s - cut.start_s))));
  EXPECT_GT(c.emitted, std::uint64_t(pp.capacity));  // the ring went round ...
  EXPECT_GT(c.overwritten, 0u);                      // ... and wrapped over live particles,
  EXPECT_GT(c.expired, 0u);                          // some outlived the drain,
  EXPECT_GT(c.aspirated, 0u);                        // the suction took its quota
  EXPECT_EQ(c.alive, 0u);
  EXPECT_GT(alive_at_stop, 0u);
  EXPECT_GE(drained_at, 0.0);
  EXPECT_LE(drained_at, quota_allowed_at);
}

// ---- contact-sweep -----------------------------------------------------------------------------

// The header of scenarios/hard/contact-sweep.toml derives the bounds: no centre inside the tip;
// overlaps unbounded (up to coincident) while the tip bulldozes, held to the pass-through bound
// from two drag times after it is lifted (the stacks it leaves spread at the speed limit, then
// drag takes the speed out) and to the resting bound at the end.
TEST(BleedingHardCases, ContactSweep) {
  Scene scene = load_hard("contact-sweep");
  ASSERT_TRUE(scene.effects.has<ContactParams>());
  ASSERT_FALSE(scene.effects.has<SuctionParams>());
  const ParticleParams& pp = scene.effects.get<ParticleParams>();
  const double step_s = 1.0 / resolve_particles(scene).steps_per_s, d = pp.diameter_mm;
  // Every leg of the path moves the tip more than a diameter a sub-step (and less than its body's
  // radius, so what it lands on is pushed ahead of it, not jumped over).
  double slowest = 1e300, fastest = 0.0;
  for (std::size_t i = 1; i < scene.tips.size(); ++i) {
    const TipPoint& a = scene.tips[i - 1];
    const TipPoint& b = scene.tips[i];
    const double speed = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm) / (b.t_s - a.t_s);
    slowest = std::min(slowest, speed);
    fastest = std::max(fastest, speed);
  }
  ASSERT_GT(slowest * step_s, d);
  ASSERT_LT(fastest * step_s, test::tip_body_mm(scene));
  ASSERT_GT(slowest, pp.max_speed_mm_s);
  const double lifted_s = scene.tips.back().t_s, touched_s = scene.tips.front().t_s;
  ASSERT_GT(touched_s, pp.bleed_s);
  Expect expect;
  expect.overlap_unbounded_until_s = lifted_s + 2.0 / pp.drag_per_s;
  // How much blood the tip had about it: the most live centres within a diameter of its body.
  const ParticleModel m = resolve_particles(scene).model;
  const float body = test::tip_body_mm(scene);
  int most_near = 0;
  std::uint64_t emitted_before = 0;
  const auto each_frame = [&](const Particles& p) {
    if (p.t_s < touched_s) emitted_before = p.counts.emitted;
    const std::optional<ToolSample> tip = test::tip_after_steps(scene, steps_by(scene, p.t_s));
    if (!tip) return;
    int near = 0;
    for (int s = 0; s < p.slots(); ++s)
      near += is_alive(m, p.age[s]) &&
              std::hypot(p.position[2 * s] - tip->x_mm, p.position[2 * s + 1] - tip->y_mm) < body + d;
    most_near = std::max(most_near, near);
  };
  RunSummary r;
  run_and_check("contact-sweep", scene, expect, &r, each_frame);
  if (HasFatalFailure()) return;
  std::cout << "  the tip moves " << slowest * step_s / d << " to " << fastest * step_s / d
            << " diameters a sub-step; at most " << most_near << " particles within a diameter of its body"
            << std::endl;
  EXPECT_GT(r.tip_frames, 10);
  EXPECT_GT(most_near, 10);
  EXPECT_EQ(emitted_before, r.final_counts.emitted);        // the pool was all there before the tip
  EXPECT_EQ(r.final_counts.alive, r.final_counts.emitted);  // and contact only moves blood
}

// ---- pulse-spurt -------------------------------------------------------------------------------

constexpr double kPi = 3.14159265358979323846;

// The blood an arterial cut without clotting has given by t, mm³: its mean flow times the
// waveform's integral over the part of its bleeding before t, in closed form
// (∫ sin(ωu) du over [t₀, t₀ + s] = (cos ωt₀ − cos ω(t₀ + s)) / ω, and likewise at 2ω).
double pulsed_blood_mm3(const PulseParams& pulse, const Cut& cut, double t_s) {
  const double s = std::clamp(t_s - cut.start_s, 0.0, cut.bleed_s), t0 = cut.start_s, t1 = t0 + s;
  const double w = 2.0 * kPi * pulse.heart_rate_per_min / 60.0;
  const double beat = s + pulse.systolic / w * (std::cos(w * t0) - std::cos(w * t1)) +
                      pulse.dicrotic / (2.0 * w) * (std::cos(2.0 * w * t0) - std::cos(2.0 * w * t1));
  return cut.wound_mm * cut.flow_mm3_per_s_per_mm * beat;
}

// The spurt limit's own arithmetic (core/effects/pulse/pulse_params.cpp's rule, written out).
double fastest_spurt(const PulseParams& pulse, const ParticleParams& p, double speed_mm_s) {
  return (1.0 + pulse.systolic + pulse.dicrotic) * speed_mm_s + std::sqrt(2.0) * p.velocity_jitter_mm_s;
}

TEST(BleedingHardCases, PulseSpurt) {
  Scene scene = load_hard("pulse-spurt");
  ASSERT_TRUE(scene.effects.has<PulseParams>());
  const PulseParams pulse = scene.effects.get<PulseParams>();
  const ParticleParams pp = scene.effects.get<ParticleParams>();
  const std::vector<Cut> cuts = scene.cuts;
  // The premises: the extremes the rules allow, and the spurt at its limit to the last bit.
  EXPECT_EQ(pulse.heart_rate_per_min, 300.0);
  EXPECT_LT(pulse.systolic + pulse.dicrotic, 1.0);
  EXPECT_GE(pulse.systolic + pulse.dicrotic, 0.9999);
  EXPECT_LT(pulse.dicrotic, pulse.systolic);
  const double speed = std::hypot(pp.velocity_x_mm_s, pp.velocity_y_mm_s);
  EXPECT_LE(fastest_spurt(pulse, pp, speed), pp.max_speed_mm_s);
  EXPECT_GT(fastest_spurt(pulse, pp, std::nextafter(speed, 1e9)), pp.max_speed_mm_s);
  EXPECT_GT(pp.velocity_jitter_mm_s, 0.0);
  ASSERT_GE(cuts.size(), 3u);
  for (const Cut& cut : cuts) {
    ASSERT_TRUE(cut.arterial);
    ASSERT_EQ(cut.clot_s, 0.0);  // the closed form above has no clotting
  }
  // The waveform's extremes, sampled every 10⁻⁶ of a beat: the peak spurt, and the least flow.
  double w_max = 0.0, w_min = 2.0;
  for (int i = 0; i < 1000000; ++i) {
    const double w = pulse_waveform(pulse, i / 1e6 / (pulse.heart_rate_per_min / 60.0));
    w_max = std::max(w_max, w), w_min = std::min(w_min, w);
  }
  const double volume = pp.particle_volume_mm3, n_cuts = double(cuts.size());
  // A float32 emission and speed limit are each a few roundings from the exact: 2⁻²⁰ of the limit.
  const double speed_bound = pp.max_speed_mm_s * (1.0 + std::ldexp(1.0, -20));
  const ParticleModel m = resolve_particles(scene).model;
  std::uint64_t before = 0;
  double fastest = 0.0, most_behind = 0.0;
  const auto each_frame = [&](const Particles& p) {
    for (int s = 0; s < p.slots(); ++s)
      if (is_alive(m, p.age[s])) fastest = std::max(fastest, p.speed(s));
    ASSERT_LE(fastest, speed_bound) << "t = " << p.t_s;
    const std::uint64_t emitted = p.counts.emitted;
    ASSERT_GE(emitted, before) << "t = " << p.t_s;
    before = emitted;
    double exact = 0.0;  // Σ_c B_c(t) / V
    for (const Cut& cut : cuts) exact += pulsed_blood_mm3(pulse, cut, p.t_s) / volume;
    // Each cut emits floor(B_c / V): between B_c/V − 1 and B_c/V (1e-6: the double arithmetic).
    ASSERT_LE(double(emitted), exact + 1e-6) << "t = " << p.t_s;
    ASSERT_GT(double(emitted), exact - n_cuts - 1e-6) << "t = " << p.t_s;
    most_behind = std::max(most_behind, exact - double(emitted));
  };
  RunSummary r;
  run_and_check("pulse-spurt", scene, Expect{}, &r, each_frame);
  if (HasFatalFailure()) return;
  double steady = 0.0, beating = 0.0;
  for (const Cut& cut : cuts) {
    steady += cut.wound_mm * cut.flow_mm3_per_s_per_mm * cut.bleed_s / volume;
    beating += pulsed_blood_mm3(pulse, cut, 1e9) / volume;
  }
  std::cout << "  waveform " << w_min << " to " << w_max << " of the mean flow; the peak spurt "
            << w_max * speed + std::sqrt(2.0) * pp.velocity_jitter_mm_s << " mm/s, the fastest seen " << fastest
            << " mm/s (limit " << pp.max_speed_mm_s << "); emitted " << r.final_counts.emitted
            << " of the closed form's " << beating << " (a steady flow's " << steady << "), at most " << most_behind
            << " behind it" << std::endl;
  EXPECT_GT(w_min, 0.0);                          // the flow never stops
  EXPECT_GT(std::abs(beating - steady), n_cuts);  // the beat shows in the totals: not all whole beats
}

// ---- vessel-edges ------------------------------------------------------------------------------

// The map scenarios/textures/vessel-edges-16x8.png holds (its README): 0 or 1 at pixel (i, j).
double edges_map(int i, int j) {
  if (i == 2 && j == 6) return 1.0;   // the lone full pixel
  if (i < 6) return 0.0;              // the step
  if (i >= 12 && j <= 2) return 0.0;  // the notch
  return 1.0;
}

// The map's mean along a wound, exactly, and the bound on the midpoint rule's error in it.
struct WoundMean {
  double exact;   // (1/length) ∫ ρ ds
  double tv;      // the total variation of dρ/dτ along the wound, τ ∈ [0, 1] its parameter
  int midpoints;  // the library's n = ⌈4 · length / pixel⌉
  double bound() const { return tv / (8.0 * midpoints * midpoints); }
};

// The test's own reading of the map (docs/bleeding.md: bilinear between pixel centres, held flat
// beyond the outermost): in pixel coordinates u = x / pixel − ½, clamped to [0, W − 1].
double bilinear(const Domain& d, double x_mm, double y_mm) {
  const double u = std::clamp(x_mm * d.width_px / d.width_mm - 0.5, 0.0, d.width_px - 1.0);
  const double v = std::clamp(y_mm * d.height_px / d.height_mm - 0.5, 0.0, d.height_px - 1.0);
  const int i = std::min(int(std::floor(u)), d.width_px - 2), j = std::min(int(std::floor(v)), d.height_px - 2);
  const double fx = u - i, fy = v - j;
  return (1 - fx) * (1 - fy) * edges_map(i, j) + fx * (1 - fy) * edges_map(i + 1, j) +
         (1 - fx) * fy * edges_map(i, j + 1) + fx * fy * edges_map(i + 1, j + 1);
}

// Along x(τ) = a + τ (b − a), τ ∈ [0, 1], the clamped pixel coordinates are linear (or constant)
// between the τ where either crosses a whole number in [0, W − 1] (the clamps are two of them), so
// on each such piece the bilinear map is a quadratic in τ: Simpson's rule integrates it exactly, and
// its three values give its derivative at both ends and its curvature.
WoundMean wound_mean(const Scene& scene, const Cut& cut) {
  const Domain& d = scene.domain;
  const double a = cut.wound_angle_deg * kPi / 180.0, half = cut.wound_mm / 2.0;
  const double x0 = cut.x_mm - half * std::cos(a), y0 = cut.y_mm - half * std::sin(a);
  const double dx = 2.0 * half * std::cos(a), dy = 2.0 * half * std::sin(a);
  std::vector<double> cuts_at{0.0, 1.0};
  const auto crossings = [&](double start_px, double span_px, int pixels) {
    if (span_px == 0.0) return;
    for (int k = 0; k < pixels; ++k) {
      const double tau = (k - start_px) / span_px;
      if (tau > 0.0 && tau < 1.0) cuts_at.push_back(tau);
    }
  };
  crossings(x0 * d.width_px / d.width_mm - 0.5, dx * d.width_px / d.width_mm, d.width_px);
  crossings(y0 * d.height_px / d.height_mm - 0.5, dy * d.height_px / d.height_mm, d.height_px);
  std::sort(cuts_at.begin(), cuts_at.end());
  const auto g = [&](double tau) { return bilinear(d, x0 + tau * dx, y0 + tau * dy); };
  WoundMean out{
      0.0, 0.0,
      std::max(1, int(std::ceil(4.0 * cut.wound_mm / std::min(d.width_mm / d.width_px, d.height_mm / d.height_px))))};
  double slope_before = 0.0;
  for (std::size_t k = 0; k + 1 < cuts_at.size(); ++k) {
    const double ta = cuts_at[k], tb = cuts_at[k + 1], len = tb - ta;
    if (len <= 0.0) continue;
    const double ga = g(ta), gm = g((ta + tb) / 2.0), gb = g(tb);
    out.exact += len * (ga + 4.0 * gm + gb) / 6.0;
    const double curvature = 4.0 * (ga - 2.0 * gm + gb) / (len * len);  // g''
    const double slope_a = (-3.0 * ga + 4.0 * gm - gb) / len, slope_b = slope_a + curvature * len;
    if (k > 0) out.tv += std::abs(slope_a - slope_before);  // the kink where two pieces meet
    out.tv += std::abs(curvature) * len;                    // the slope's change along the piece
    slope_before = slope_b;
  }
  return out;
}

TEST(BleedingHardCases, VesselEdges) {
  Scene scene = load_hard("vessel-edges");
  ASSERT_TRUE(scene.effects.has<VesselParams>() && scene.effects.has<PulseParams>());
  const Domain& d = scene.domain;
  // The map as read is the map described, pixel for pixel (no resampling: one PNG pixel a pixel).
  ASSERT_EQ(scene.vessel_density.size(), std::size_t(d.width_px) * d.height_px);
  for (int j = 0; j < d.height_px; ++j)
    for (int i = 0; i < d.width_px; ++i)
      ASSERT_EQ(scene.vessel_density[std::size_t(j) * d.width_px + i], float(edges_map(i, j))) << i << ", " << j;
  const PulseParams pulse = scene.effects.get<PulseParams>();
  ASSERT_EQ(pulse.arterial_density, 1.0);
  const double volume = scene.effects.get<ParticleParams>().particle_volume_mm3;
  struct Expected {
    double low, high;  // the cut's particles: [N·ρ − 1 − E, N·ρ + E]
    double window_end_s;
  };
  std::vector<Expected> expected;
  int zero = -1, arterial = -1, beyond = 0;
  for (std::size_t c = 0; c < scene.cuts.size(); ++c) {
    const Cut& cut = scene.cuts[c];
    const WoundMean mean = wound_mean(scene, cut);
    const Cut bleeding = with_vessels(scene, cut);
    // The library's mean against the exact one, within the midpoint rule's bound (and rounding).
    EXPECT_NEAR(bleeding.vessel_density, mean.exact, mean.bound() + 1e-12) << "cut " << c;
    EXPECT_EQ(bleeding.arterial, mean.exact >= 1.0) << "cut " << c;
    if (bleeding.arterial) {
      arterial = int(c);
      EXPECT_EQ(bleeding.vessel_density, 1.0);
    }
    if (mean.exact == 0.0) {
      zero = int(c);
      EXPECT_EQ(bleeding.vessel_density, 0.0);
    }
    // At full density: N particles, steady or beating.
    const double full = (bleeding.arterial ? pulsed_blood_mm3(pulse, cut, 1e9)
                                           : cut.wound_mm * cut.flow_mm3_per_s_per_mm * cut.bleed_s) /
                        volume;
    if (bleeding.arterial) {
      const double steady = cut.wound_mm * cut.flow_mm3_per_s_per_mm * cut.bleed_s / volume;
      EXPECT_GT(std::abs(full - steady), 1.0 + full * mean.bound()) << "the beat must show in its count";
    }
    const double half = cut.wound_mm / 2.0, a = cut.wound_angle_deg * kPi / 180.0;
    for (const double side : {-1.0, 1.0}) {
      const double x = cut.x_mm + side * half * std::cos(a), y = cut.y_mm + side * half * std::sin(a);
      beyond += x < 0.0 || x > d.width_mm || y < 0.0 || y > d.height_mm;
    }
    const double e = full * mean.bound(), n = full * mean.exact;
    expected.push_back({n - 1.0 - e - 1e-9, n + e + 1e-9, cut.start_s + 0.5});
    std::cout << "  cut " << c << ": mean density " << mean.exact << " (library " << bleeding.vessel_density
              << ", midpoint bound " << mean.bound() << " over " << mean.midpoints << " steps)"
              << (bleeding.arterial ? ", arterial" : "") << "; " << n << " particles, ± " << e << std::endl;
    if (c + 1 < scene.cuts.size()) {
      ASSERT_GE(scene.cuts[c + 1].start_s, cut.start_s + 0.5);  // one at a time
    }
  }
  ASSERT_GE(zero, 0);
  ASSERT_GE(arterial, 0);
  EXPECT_GT(beyond, 2);  // wounds reach past the panel's edges

  std::size_t next = 0;
  std::uint64_t before = 0;
  std::vector<std::uint64_t> bled;
  const auto each_frame = [&](const Particles& p) {
    if (next < expected.size() && std::abs(p.t_s - expected[next].window_end_s) < 1e-9) {
      bled.push_back(p.counts.emitted - before);
      before = p.counts.emitted;
      ++next;
    }
  };
  RunSummary r;
  run_and_check("vessel-edges", scene, Expect{}, &r, each_frame);
  if (HasFatalFailure()) return;
  ASSERT_EQ(bled.size(), expected.size());
  for (std::size_t c = 0; c < bled.size(); ++c) {
    std::cout << "  cut " << c << " bled " << bled[c] << std::endl;
    EXPECT_GE(double(bled[c]), expected[c].low) << "cut " << c;
    EXPECT_LE(double(bled[c]), expected[c].high) << "cut " << c;
  }
  EXPECT_EQ(bled[std::size_t(zero)], 0u);
}

}  // namespace
}  // namespace bleedsim