// The film with depth (docs/particles.md#a-film-with-depth) against hydrostatics. Its parcels of
// volume V make a film of depth h(x) = Σ V·W(|x − x_j|) (W the 2D Wendland C2 kernel of support
// R, the panel's edges mirroring the film), and each is pushed by −g_n·∇h. On a panel tilted so
// that gravity has g_t along it and g_n into it, a pool against the floor with no grip comes to
// rest where g_n·∇h = g_t: a wedge whose surface slopes at s = g_t/g_n, of length L and depth
// h₀ = s·L at the floor, holding the pool's volume V_p over the panel's width w:
//   h₀ = √(2·V_p·s / w).
// The wedge is exact but within a kernel's reach of its tip, where the smoothed depth must turn
// to nothing over R instead of at a point: the volume there differs from the wedge's by at most
// the wedge's last R, w·s·R²/2, and that volume over the pool moves its depth at the floor (and
// everywhere, the slope being fixed) by at most s·R²/(2·L). That is the bound here, at every
// particle size: it shrinks as d², so the depth converges at second order.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "core/effects/cuts.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/runtime/tissue.h"
#include "core/simulation/simulation.h"
#include "tests/effects/particle_box.h"
#include "tests/runtime/field_values.h"

namespace bleedsim {
namespace {

using test::ParticleBox;
using test::Point;

// An 8 × 12 mm panel, tilted so that 1000 mm/s² pull along it and 9950 into it (s = 0.1005), and
// 4 mm³ of blood: a wedge 3.15 mm long, 0.317 mm deep at the floor, nearly three layers of the
// contact's one-layer film (0.115 mm), well inside the panel.
constexpr double kWidth = 8.0, kHeight = 12.0, kPoolMm3 = 4.0, kAlong = 1000.0, kNormal = 9950.0;
constexpr double kSlope = kAlong / kNormal;

double wedge_depth_at_floor() { return std::sqrt(2.0 * kPoolMm3 * kSlope / kWidth); }

// The wedge's bound at particles of diameter d (above).
double wedge_bound(double d) {
  const double support = kKernelSupport * d, length = wedge_depth_at_floor() / kSlope;
  return kSlope * support * support / (2.0 * length);
}

// Hydrostatics alone: no grip, no sleep; each particle a parcel of the same one-layer film
// (V ∝ d², as the study refines the particles).
ParticleParams pool_params(double d) {
  ParticleParams p;
  p.film_depth = true;
  p.cohesion_mm3_s2 = 0.0;
  p.yield_mm2_s2 = 0.0;
  p.pinning_mm3_s2 = 0.0;
  p.rest_s = 0.0;
  p.diameter_mm = d;
  p.particle_volume_mm3 = ParticleParams{}.particle_volume_mm3 * (d / 0.2) * (d / 0.2);
  p.gravity_y_mm_s2 = kAlong;
  p.gravity_normal_mm_s2 = kNormal;
  return p;
}

double wendland(double r, double support) {
  const double q = r / support;
  if (q >= 1.0) return 0.0;
  return 7.0 / (M_PI * support * support) * std::pow(1.0 - q, 4) * (1.0 + 4.0 * q);
}

// The pool's depth a height `up` mm above the floor: the film of its parcels and their images
// across the floor, averaged across the middle half of the panel (a kernel's reach and more from
// the side walls).
double pool_depth(const ParticleBox& box, const ParticleParams& p, double up) {
  const double support = kKernelSupport * p.diameter_mm, y = kHeight - up;
  double sum = 0.0;
  int samples = 0;
  for (double x = kWidth / 4; x <= 3 * kWidth / 4; x += 0.05, ++samples)
    for (int i = 0; i < box.size(); ++i) {
      const Point q = box.position(i);
      sum += p.particle_volume_mm3 * (wendland(std::hypot(x - q.x, y - q.y), support) +
                                      wendland(std::hypot(x - q.x, y - (2.0 * kHeight - q.y)), support));
    }
  return sum / samples;
}

struct Pool {
  double floor_mm, one_up_mm, fastest_mm_s;
};

// The pool's blood as a block against the floor, slumped for 3 s (the wedge relaxes as a diffusion
// of g_n·h/γ ≈ 30 mm²/s over its 3 mm: in about 0.3 s).
Pool settled_pool(double d) {
  const ParticleParams p = pool_params(d);
  const Scene scene = test::box_scene(kWidth, kHeight, p);
  const int n = int(std::lround(kPoolMm3 / p.particle_volume_mm3)), columns = int(kWidth / d);
  std::vector<Point> points = test::hex_block(scene, columns, 2 * n / columns + 2);
  points.resize(std::size_t(n));
  ParticleBox box(scene, points);
  box.run_for(3.0);
  double fastest = 0.0;
  for (int i = 0; i < n; ++i) fastest = std::max(fastest, box.speed(i));
  return {pool_depth(box, p, 0.0), pool_depth(box, p, 1.0), fastest};
}

void expect_wedge(double d, const Pool& pool) {
  const double h0 = wedge_depth_at_floor(), bound = wedge_bound(d);
  std::cout << "d " << d << " mm: depth at the floor " << pool.floor_mm << " mm, 1 mm up " << pool.one_up_mm
            << " (the wedge: " << h0 << ", " << h0 - kSlope << "; bound " << bound << "); fastest "
            << pool.fastest_mm_s << " mm/s" << std::endl;
  EXPECT_NEAR(pool.floor_mm, h0, bound) << "d " << d;
  EXPECT_NEAR(pool.one_up_mm, h0 - kSlope, bound) << "d " << d;
}

// The pair's push is g_n·V·|dW/dr|, dW/dr = −140·q·(1 − q)³/(π·R³): the constant the model derives
// and the shape the kernel has, to float rounding, nothing at a parcel's own place and at the
// kernel's reach.
TEST(FilmDepth, APushIsTheHydrostaticPressuresGradient) {
  const ParticleParams p = pool_params(0.2);
  const ParticleModel m = resolve_particles(test::box_scene(kWidth, kHeight, p)).model;
  const double support = kKernelSupport * p.diameter_mm;
  ASSERT_TRUE(has_depth(m));
  for (double q : {0.05, 0.25, 0.5, 0.75, 0.95}) {
    const double gradient = 140.0 * q * std::pow(1.0 - q, 3) / (M_PI * support * support * support);
    EXPECT_NEAR(film_push(m, float(q * support)), kNormal * p.particle_volume_mm3 * gradient,
                1e-5 * kNormal * p.particle_volume_mm3 * gradient)
        << "q " << q;
  }
  EXPECT_EQ(film_push(m, 0.0f), 0.0f);
  // At the reach, q = r/R is 1 but for float's rounding of 1/R (2⁻²⁴), and (1 − q)³ under 1e-21.
  EXPECT_LE(film_push(m, float(support)), 1e-21f * m.pressure);
  EXPECT_EQ(film_push(m, float(2.0 * support)), 0.0f);
}

// Momentum: a pair's pushes are equal and opposite, bit for bit, as the contact's are.
TEST(FilmDepth, APairPushesEquallyAndOppositely) {
  const ParticleModel m = resolve_particles(test::box_scene(kWidth, kHeight, pool_params(0.2))).model;
  const std::uint32_t born = 0u;  // a film with depth's birth is its rest word: 0 is in the film
  PairSums one, other;
  add_pair(m, 0.13f, -0.21f, 0.0f, 0.0f, pair_growth(m, born, born), 1, 0.0f, 0.0f, 2, &one);
  add_pair(m, -0.13f, 0.21f, 0.0f, 0.0f, pair_growth(m, born, born), 2, 0.0f, 0.0f, 1, &other);
  EXPECT_GT(std::hypot(one.ax, one.ay), 0.0);
  EXPECT_EQ(one.ax, -other.ax);
  EXPECT_EQ(one.ay, -other.ay);
}

TEST(FilmDepth, APoolOnATiltedPanelIsTheHydrostaticWedge) {
  const Pool pool = settled_pool(0.2);
  expect_wedge(0.2, pool);
  // The film thickens: the pool is deeper than the one layer the contact's particles can make.
  const ParticleModel layer = resolve_particles(test::box_scene(kWidth, kHeight, ParticleParams{})).model;
  EXPECT_GT(pool.floor_mm, 2.0 * ParticleParams{}.particle_volume_mm3 / (std::sqrt(3.0) / 2.0 * layer.diameter_sq));
}

// At twice and half the shipped size the wedge holds to its bound, which falls as d².
TEST(FilmDepth, TheWedgeConvergesAsTheParticlesShrink) {
  for (double d : {0.4, 0.1}) expect_wedge(d, settled_pool(d));
}

// The film field (splat/thickness) reports the pool's depth: a cut 1 mm above the floor bleeds
// the pool's 4 mm³ in 1 s, and 3 s later the film 1 mm and 2 mm above the floor, averaged across
// the middle half of the panel, is the wedge's. The splat spreads each parcel over its own
// footprint (a symmetric kernel of the diameter), which keeps a linear profile as it is.
TEST(FilmDepth, TheFilmFieldReportsThePoolsDepth) {
  Scene scene;
  scene.name = "pool";
  scene.domain = Domain{160, 240, kWidth, kHeight};
  scene.duration_s = 4.0;
  scene.frame_rate_hz = 30.0;
  scene.tissue = procedural_tissue(scene.domain.width_px, scene.domain.height_px, 1);
  ParticleParams p = pool_params(0.2);
  p.flow_mm3_per_s_per_mm = kPoolMm3;
  p.bleed_s = 1.0;
  p.velocity_jitter_mm_s = 0.0;
  scene.effects.set(p);
  scene.cuts.push_back(cut_at(scene, kWidth / 2, kHeight - 1.0, 0.0));
  Simulation sim(scene, BackendChoice{BackendChoice::Want::cpu, 2});
  while (sim.frames_done() < scene.frame_count()) sim.step();
  const std::vector<float> film = test::field_values<float>(sim, "splat/thickness");
  const Domain& d = scene.domain;
  const auto film_at = [&](double up) {
    const int row = int((kHeight - up) / kHeight * d.height_px);
    double sum = 0.0;
    for (int x = d.width_px / 4; x < 3 * d.width_px / 4; ++x) sum += film[std::size_t(row * d.width_px + x)];
    return sum / (d.width_px / 2);
  };
  const double h0 = wedge_depth_at_floor(), bound = wedge_bound(p.diameter_mm);
  std::cout << "film 1 mm up " << film_at(1.0) << " mm, 2 mm up " << film_at(2.0) << " (the wedge: " << h0 - kSlope
            << ", " << h0 - 2 * kSlope << "; bound " << bound << ")" << std::endl;
  EXPECT_NEAR(film_at(1.0), h0 - kSlope, bound);
  EXPECT_NEAR(film_at(2.0), h0 - 2 * kSlope, bound);
}

// The grip of a film with depth is a yield stress over each parcel's area and a pinning along
// the contact line: per unit mass (τ_y/ρ + q_p·|∇c|)/h. Far inside a uniform film (no colour
// gradient, no pressure gradient) a parcel feels gravity g_t and that grip alone, so the film is a
// Bingham film: it stays where it is while g_t·h ≤ τ_y/ρ, and above that slides at the discrete
// terminal speed v_T = (g_t − (τ_y/ρ)/h·(1 + γ·dt))/γ (the drag and the grip taken implicitly, as a
// lone particle's: tests/effects/particle_rest_test.cpp). A 12 × 12 mm square of parcels on a
// hexagonal lattice, its spacing set for a depth 0.8 and 1.25 times the yield depth
// (τ_y/ρ)/g_t = 0.05 mm, watched for 0.06 s: six of the drag's 1/γ, so the terminal speed is reached
// to e⁻⁶ (0.25 %). Its edges are not uniform (their pressure pushes out, the pinning holds), and
// what they do travels inwards at the film's wave speed √(g_n·h), 24 mm/s here: 1.5 mm in that
// time. The interior is what lies further than 2.5 mm from every edge; the test sums its depth
// itself.
TEST(FilmDepth, AFilmThinnerThanItsYieldDepthStaysAndAThickerOneSlidesAtItsTerminalSpeed) {
  for (const double share : {0.8, 1.25}) {
    ParticleParams p = pool_params(0.2);
    p.yield_mm2_s2 = ParticleParams{}.yield_mm2_s2;
    p.pinning_mm3_s2 = ParticleParams{}.pinning_mm3_s2;
    const double yield_depth = p.yield_mm2_s2 / kAlong, depth = share * yield_depth;
    const double spacing = std::sqrt(p.particle_volume_mm3 / (depth * std::sqrt(3.0) / 2.0)) / p.diameter_mm;
    const Scene scene = test::box_scene(20.0, 40.0, p);
    const int columns = int(12.0 / (spacing * p.diameter_mm));
    std::vector<Point> points = test::hex_block(scene, columns, int(12.0 / (spacing * p.diameter_mm * 0.866)), 4.0, spacing);
    for (Point& q : points) q.y -= 20.0;  // well above the floor
    ParticleBox box(scene, points);
    box.run_for(0.06);
    const double support = kKernelSupport * p.diameter_mm, dt = box.dt(), margin = 2.5;
    double slowest = 1e9, fastest = 0.0, worst = 0.0;
    int interior = 0;
    for (int i = 0; i < box.size(); ++i) {
      const Point at = points[std::size_t(i)];
      if (at.x < 4.0 + margin || at.x > 16.0 - margin || at.y < 8.0 + margin || at.y > 20.0 - margin) continue;
      double h = 0.0;
      for (int j = 0; j < box.size(); ++j)
        h += p.particle_volume_mm3 * wendland(std::hypot(box.position(i).x - box.position(j).x,
                                                         box.position(i).y - box.position(j).y),
                                              support);
      const double terminal = std::max(0.0, (kAlong - p.yield_mm2_s2 / h * (1.0 + p.drag_per_s * dt)) / p.drag_per_s);
      slowest = std::min(slowest, box.speed(i));
      fastest = std::max(fastest, box.speed(i));
      worst = std::max(worst, std::abs(box.speed(i) - terminal));
      ++interior;
    }
    std::cout << "a film " << share << " × the yield depth: " << interior << " interior parcels at " << slowest << " to "
              << fastest << " mm/s, at most " << worst << " mm/s from their terminal speed" << std::endl;
    ASSERT_GT(interior, 100);
    if (share < 1.0) EXPECT_EQ(fastest, 0.0);
    else EXPECT_LE(worst, 0.01 * (kAlong - p.yield_mm2_s2 / depth) / p.drag_per_s);
  }
}

}  // namespace
}  // namespace bleedsim
