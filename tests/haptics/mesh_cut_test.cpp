// Cuts on a tissue mesh (core/haptics/haptics.cpp with a scene's mesh): the stylus' contact becomes
// the proxy's triangle and barycentric weights, its uv, and the texel a cut is made at; a stroke's
// cuts are spaced along the surface. The reference is the parametric surface's own uv, worked out
// here from its closed form, with the faceting's error derived beside each test.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

#include "core/haptics/haptics.h"
#include "core/haptics/trace_replay.h"
#include "core/io/scenario.h"
#include "tests/mesh/meshes_in_code.h"
#include "tests/runtime/scenes_in_code.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

using Eigen::Vector3d;

// A cylinder patch of radius 10 mm over 1.2 rad and 8 mm high, in 6 facets around (each turning
// a = 0.1 rad either side of its middle) and 4 rows: coarse, so that the faceting shows. Its uv is
// (θ / 1.2, z / 8); its outside (∂P/∂v × ∂P/∂u) faces the axis, so the tissue lies beyond radius 10.
// The texture: 240 × 96 texels over the surface's 12 × 8 mm (0.05 and 0.083 mm a texel).
constexpr double kRadius = 10.0, kSpan = 1.2, kHeight = 8.0;
constexpr int kFacets = 6, kRows = 4;
constexpr double kHalfFacet = kSpan / kFacets / 2;  // a

Scene cylinder_scene() {
  Scene scene = test::scene_in_code(true);
  scene.domain = Domain{240, 96, kRadius * kSpan, kHeight};
  scene.mesh = std::make_shared<const MeshSurface>(test::cylinder_patch(kRadius, kSpan, kHeight, kFacets, kRows));
  scene.haptics = HapticParams{};  // cuts every 1 mm with button 0x1
  return scene;
}

// The surface's point at angle θ and height z, and the direction out of the tissue there (to the axis).
Vector3d on_cylinder(double theta, double z, double radius = kRadius) {
  return Vector3d(radius * std::cos(theta), radius * std::sin(theta), z);
}

DeviceSample sample(const Vector3d& tip_mm, std::uint8_t buttons) { return DeviceSample{tip_mm / 1000.0, buttons}; }

// Where the faceting moves a cut. The facet from θ_m − a to θ_m + a is the chord between its corners;
// its point with barycentric split s = w₊ − w₋ ∈ [−1, 1] is at polar angle θ_m + atan(s·tan a), and
// the shading normal there (the corners' radial normals by the same weights: every interior vertex
// of this grid has three triangles of equal area on either side) points along that same radius. So
// the proxy of a tip at angle θ lies on the tip's own radius, at the tip's height (the normal has no
// z), and its uv is linear in s: u = (θ_m + s·a) / span against the surface's θ / span. The cut's u
// is off by at most max over s of |s·a − atan(s·tan a)| / span, and its v not at all; in texels,
// times the texture's width.
double faceting_error_texels(const Domain& d) {
  double worst = 0;
  for (int k = 0; k <= 2000; ++k) {
    const double s = -1.0 + k / 1000.0;
    worst = std::max(worst, std::fabs(s * kHalfFacet - std::atan(s * std::tan(kHalfFacet))));
  }
  return worst / kSpan * d.width_px;
}

// The texel of a cut, and the texel the surface's uv at (θ, z) gives.
Eigen::Vector2d cut_texel(const Cut& cut, const Domain& d) {
  return Eigen::Vector2d(cut.x_mm / d.width_mm * d.width_px, cut.y_mm / d.height_mm * d.height_px);
}
Eigen::Vector2d analytic_texel(double theta, double z, const Domain& d) {
  return Eigen::Vector2d(theta / kSpan * d.width_px, z / kHeight * d.height_px);
}

// The stylus comes in along the surface's normal at (θ, z), from 3 mm out, 0.02 mm a tick, with the
// cutting button held: its first cut, on the first tick of contact, is at the texel of (θ, z) within
// the faceting's error, and that within half a texel. Over the interior (away from the patch's edge
// columns and rows, whose vertices have triangles on one side only).
TEST(MeshCut, AStabCutsAtTheSurfacesUvWithinHalfATexel) {
  const Scene scene = cylinder_scene();
  const double bound = faceting_error_texels(scene.domain);
  double worst = 0;
  int cuts = 0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 8; ++j) {
      const double theta = kSpan * (0.2 + 0.6 * i / 40.0), z = kHeight * (0.3 + 0.4 * j / 8.0);
      HapticLoop loop(scene);
      std::optional<Cut> cut;
      for (int n = 0; n <= 200 && !cut; ++n)
        cut = loop.tick(sample(on_cylinder(theta, z, kRadius - 3.0 + 0.02 * n), 0x1)).cut;
      ASSERT_TRUE(cut) << "θ " << theta << ", z " << z;
      ++cuts;
      const Eigen::Vector2d error = cut_texel(*cut, scene.domain) - analytic_texel(theta, z, scene.domain);
      ASSERT_LE(std::fabs(error.x()), bound + 1e-9) << "θ " << theta << ", z " << z;
      ASSERT_LE(std::fabs(error.y()), 1e-9) << "θ " << theta << ", z " << z;
      worst = std::max(worst, error.cwiseAbs().maxCoeff());
    }
  std::cout << cuts << " stabs into 6 facets of a 10 mm cylinder: the cut's texel within " << worst
            << " texels of the surface's uv (faceting bound " << bound << ", acceptance 0.5)\n";
  EXPECT_LE(bound, 0.5);
}

// A stroke round the cylinder, 1 mm deep at 20 mm/s, from θ = 0.25 to 0.95 rad at mid-height: every
// cut is at the surface's uv of the tip's radius (as above), and cuts are spaced along the surface.
// The haptic loop cuts once the chord between the proxies of this and the last cut reaches 1 mm. The
// proxies lie on the facets, whose path between two angles is no longer than the circle's arc
// between them, so the arc between consecutive cuts is at least 1 mm. The tick before, the chord
// was under 1 mm; a tick moves the proxy by at most the tip's step (0.02 mm, scaled by r / (r + 1)
// < 1); a chord across at most one corner is at least cos a of the facets' path, and the path at
// least sin a / a of the arc: the arc is at most (1 mm + 0.02 mm) · a / (sin a · cos a).
TEST(MeshCut, AStrokesCutsFollowTheSurface) {
  const Scene scene = cylinder_scene();
  const double bound = faceting_error_texels(scene.domain), z = kHeight / 2, depth = 1.0, step = 0.02;
  HapticLoop loop(scene);
  std::vector<Cut> cuts;
  std::vector<double> tip_theta;
  const auto tick = [&](const Vector3d& tip_mm, double theta) {
    if (const std::optional<Cut> cut = loop.tick(sample(tip_mm, 0x1)).cut) {
      cuts.push_back(*cut);
      tip_theta.push_back(theta);
    }
  };
  const double from = 0.25, to = 0.95;
  for (int n = 0; n <= 200; ++n) tick(on_cylinder(from, z, kRadius - 3.0 + (3.0 + depth) * n / 200.0), from);
  const double radius = kRadius + depth, ticks = std::ceil((to - from) * radius / step);
  for (int n = 1; n <= ticks; ++n) {
    const double theta = from + (to - from) * n / ticks;
    tick(on_cylinder(theta, z, radius), theta);
  }
  const double arc_mm = (to - from) * kRadius;
  ASSERT_GE(cuts.size(), std::size_t(std::floor(arc_mm / 1.1)));
  const double most = (1.0 + step) * kHalfFacet / (std::sin(kHalfFacet) * std::cos(kHalfFacet));
  double shortest = 1e9, longest = 0;
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const Eigen::Vector2d error = cut_texel(cuts[k], scene.domain) - analytic_texel(tip_theta[k], z, scene.domain);
    ASSERT_LE(std::fabs(error.x()), bound + 1e-9) << "cut " << k;
    ASSERT_LE(std::fabs(error.y()), 1e-9) << "cut " << k;
    if (k == 0) continue;
    const double arc = (cuts[k].x_mm - cuts[k - 1].x_mm) / scene.domain.width_mm * kSpan * kRadius;
    shortest = std::min(shortest, arc);
    longest = std::max(longest, arc);
    // The wound runs the way the stroke went in the texture: along +u.
    ASSERT_NEAR(cuts[k].wound_angle_deg, 0.0, 1e-9) << "cut " << k;
  }
  std::cout << cuts.size() << " cuts along " << arc_mm << " mm of surface: arcs between them " << shortest << " to "
            << longest << " mm (bounds 1 and " << most << ")\n";
  EXPECT_GE(shortest, 1.0 - 1e-9);
  EXPECT_LE(longest, most);
}

// The flat panel as a mesh, placed where the golden stroke scenes put the panel under the stylus
// (panel point (X, Y) at device (X − origin_x, origin_y − Y, surface_z)), replays their traces as the
// plane does: the same ticks in contact and cutting, the same cuts. The proxy is the tip's foot on the
// panel (every vertex normal is +z) and the force the plane's below the energy bound, which a
// conservative field does not meet (tests/haptics/mesh_contact_test.cpp); they are computed in mm
// through barycentric weights instead of in m, so they agree to rounding, not to the bit: forces to
// 1e-12 N, depths to 1e-12 m, places and cuts to 1e-9 mm (some 1e5 ulps of a 32 mm panel, the
// weights' rounding times the panel's size), the wound's direction to 1e-6°.
TEST(MeshCut, AFlatMeshCutsWhereThePanelDoes) {
  for (const char* name : {"falcon-single-stroke", "falcon-strokes"}) {
    const Scene panel = load_scenario(test::source_dir() + "/scenarios/golden/" + name + ".toml").scene;
    const HapticParams& h = *panel.haptics;
    ASSERT_EQ(h.scale, 1.0);
    TissueMesh mesh = test::flat_panel_mesh(panel.domain.width_mm, panel.domain.height_mm);
    for (Vector3d& p : mesh.positions) p += Vector3d(-h.origin_x_mm, h.origin_y_mm, h.surface_z_mm);
    Scene on_mesh = panel;
    on_mesh.mesh = std::make_shared<const MeshSurface>(std::move(mesh));
    HapticLoop plane(panel), flat(on_mesh);
    int cuts = 0, contact = 0;
    for (std::int64_t n = 0; n < panel.haptic_ticks_through_frame(panel.frame_count() - 1); ++n) {
      const DeviceSample sample = trace_sample_at_tick(*panel.trace, n);
      const HapticStep a = plane.tick(sample), b = flat.tick(sample);
      ASSERT_EQ(a.record.contact, b.record.contact) << name << " tick " << n;
      ASSERT_EQ(a.record.cutting, b.record.cutting) << name << " tick " << n;
      ASSERT_NEAR(a.record.penetration_m, b.record.penetration_m, 1e-12) << name << " tick " << n;
      ASSERT_LE((a.record.force_N - b.record.force_N).cwiseAbs().maxCoeff(), 1e-12) << name << " tick " << n;
      if (a.record.contact) {
        ASSERT_LE((a.record.panel_mm - b.record.panel_mm).cwiseAbs().maxCoeff(), 1e-9) << name << " tick " << n;
      }
      ASSERT_EQ(a.cut.has_value(), b.cut.has_value()) << name << " tick " << n;
      contact += a.record.contact;
      if (!a.cut) continue;
      ++cuts;
      EXPECT_NEAR(a.cut->x_mm, b.cut->x_mm, 1e-9) << name << " tick " << n;
      EXPECT_NEAR(a.cut->y_mm, b.cut->y_mm, 1e-9) << name << " tick " << n;
      EXPECT_NEAR(a.cut->wound_angle_deg, b.cut->wound_angle_deg, 1e-6) << name << " tick " << n;
      EXPECT_EQ(a.cut->start_s, b.cut->start_s) << name << " tick " << n;
    }
    std::cout << name << ": " << contact << " ticks in contact, " << cuts << " cuts, the same on the flat mesh\n";
    EXPECT_GT(cuts, 3);
  }
}

}  // namespace
}  // namespace bleedsim
