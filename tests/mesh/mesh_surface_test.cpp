// Where on a tissue mesh a point is (core/mesh/mesh_surface.h): the closest point of a triangle
// against a dense sampling of it, the hierarchy's answer against every triangle's, and the uv of a
// point on a parametric cylinder patch against the facet's closed form and the smooth surface's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "core/io/mesh_obj.h"
#include "core/mesh/mesh_surface.h"
#include "tests/mesh/meshes_in_code.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

using test::cylinder_patch;

TEST(MeshSurface, TheClosestPointOfATriangleIsNoFartherThanAnyOfItsPoints) {
  const Eigen::Vector3d a(0, 0, 0), b(3, 0.5, 0), c(1, 2, 0.7);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> box(-3, 5);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d p(box(random), box(random), box(random));
    const Eigen::Vector3d w = closest_on_triangle(p, a, b, c);
    ASSERT_NEAR(w.sum(), 1.0, 1e-12);
    ASSERT_GE(w.minCoeff(), -1e-12);
    const double found = (w[0] * a + w[1] * b + w[2] * c - p).norm();
    // Every point of a 100-step barycentric grid is at least as far (to rounding).
    for (int i = 0; i <= 100; ++i)
      for (int j = 0; i + j <= 100; ++j) {
        const Eigen::Vector3d q = a + (b - a) * (i / 100.0) + (c - a) * (j / 100.0);
        ASSERT_LE(found, (q - p).norm() + 1e-12) << "trial " << trial;
      }
  }
}

TEST(MeshSurface, TheHierarchyFindsWhatEveryTriangleWouldGive) {
  const MeshSurface surface(load_tissue_mesh(test::source_dir() + "/scenarios/meshes/turbinate.obj"));
  const TissueMesh& mesh = surface.mesh();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> x(-5, 45), yz(-15, 10);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d p(x(random), yz(random), yz(random));
    double best = INFINITY;
    int best_triangle = -1;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& c = mesh.triangles[t].corner;
      const Eigen::Vector3d w = closest_on_triangle(p, mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]);
      const double d =
          (w[0] * mesh.positions[c[0]] + w[1] * mesh.positions[c[1]] + w[2] * mesh.positions[c[2]] - p).squaredNorm();
      if (d < best) best = d, best_triangle = int(t);
    }
    const SurfacePoint found = surface.closest(p);
    ASSERT_EQ(found.distance_mm, std::sqrt(best)) << "trial " << trial;
    ASSERT_EQ(found.triangle, best_triangle) << "trial " << trial;
  }
}

// The segment queries through the hierarchy against every triangle's, each found independently:
// where the segment meets the triangle's plane, and whether that point is inside the triangle (the
// same side of all three edges). Random segments on the turbinate meet no edge to within 1e-9 of
// the barycentric range, where the two could disagree.
TEST(MeshSurface, TheSegmentQueryFindsEveryTriangleItPassesThrough) {
  const MeshSurface surface(load_tissue_mesh(test::source_dir() + "/scenarios/meshes/turbinate.obj"));
  const TissueMesh& mesh = surface.mesh();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> x(-5, 45), yz(-15, 10);
  int found = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a(x(random), yz(random), yz(random)), b(x(random), yz(random), yz(random));
    std::vector<std::pair<double, int>> expected;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& c = mesh.triangles[t].corner;
      const Eigen::Vector3d &p = mesh.positions[c[0]], &q = mesh.positions[c[1]], &r = mesh.positions[c[2]];
      const Eigen::Vector3d n = (q - p).cross(r - p);
      const double along = n.dot(b - a);
      if (along == 0) continue;
      const double s = n.dot(p - a) / along;
      if (s < 0 || s > 1) continue;
      const Eigen::Vector3d at = a + s * (b - a);
      if (n.dot((q - p).cross(at - p)) >= 0 && n.dot((r - q).cross(at - q)) >= 0 && n.dot((p - r).cross(at - r)) >= 0)
        expected.emplace_back(s, int(t));
    }
    std::sort(expected.begin(), expected.end());
    const std::vector<SegmentCrossing> got = surface.crossings(a, b);
    ASSERT_EQ(got.size(), expected.size()) << "trial " << trial;
    for (std::size_t i = 0; i < got.size(); ++i) {
      ASSERT_EQ(got[i].at.triangle, expected[i].second) << "trial " << trial;
      ASSERT_NEAR(got[i].t, expected[i].first, 1e-12) << "trial " << trial;
      const auto& c = mesh.triangles[got[i].at.triangle].corner;
      const Eigen::Vector3d& w = got[i].at.barycentric;
      const Eigen::Vector3d on = w[0] * mesh.positions[c[0]] + w[1] * mesh.positions[c[1]] + w[2] * mesh.positions[c[2]];
      ASSERT_NEAR((on - (a + got[i].t * (b - a))).norm(), 0.0, 1e-9) << "trial " << trial;
    }
    found += int(got.size());
  }
  EXPECT_GT(found, 100);  // the segments do cross the sheet, often several times
}

// On the flat panel a segment through its diagonal, the edge its two triangles share, passes through
// both; one that starts or ends on it passes through it; one lying in it does not.
TEST(MeshSurface, ASegmentThroughAnEdgeOrFromTheSurfacePassesThroughIt) {
  const MeshSurface surface(load_tissue_mesh(test::source_dir() + "/scenarios/meshes/flat-panel.obj"));
  EXPECT_EQ(surface.crossings({16, -12, 1}, {16, -12, -1}).size(), 2u);  // (16, −12) is on the diagonal
  EXPECT_EQ(surface.crossings({5, -20, 0}, {5, -20, -1}).size(), 1u);
  EXPECT_EQ(surface.crossings({5, -20, 1}, {5, -20, 0}).size(), 1u);
  EXPECT_EQ(surface.crossings({5, -20, 0}, {9, -20, 0}).size(), 0u);
  EXPECT_EQ(surface.crossings({5, -20, 1}, {5, -20, 0.5}).size(), 0u);
  EXPECT_EQ(surface.crossings({40, -20, 1}, {40, -20, -1}).size(), 0u);  // past the panel's edge
}

// A point off the patch at height z (inside its height) lands on the facet nearest to it seen from
// above, a 2D question: the facet k whose chord AB (its edges at θk, θk+1) is nearest, at the
// chord's parameter t = clamp((P − A)·(B − A) / |B − A|², 0, 1); its uv is ((k + t) / n, z / h)
// exactly (the facets are flat rectangles, uv linear on each). Against the smooth surface's
// (θ / span, z / h) it is off by the facet's chord error; with n = 128 facets over 2 rad that is
// under half a texel of a 1024-texel texture (the bound for a cut's uv).
TEST(MeshSurface, TheUvOfAPointOnACylinderIsTheFacetsAndTheSurfacesWithinHalfATexel) {
  const double r = 6.0, span = 2.0, h = 20.0;
  const int n = 128, m = 16, texels = 1024;
  const MeshSurface surface(cylinder_patch(r, span, h, n, m));
  std::mt19937 random(11);
  std::uniform_real_distribution<double> angle(0.01, span - 0.01), height(0.1, h - 0.1), radius(r - 0.02, r + 0.5);
  double worst_smooth = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    const double theta = angle(random), z = height(random), rho = radius(random);
    const Eigen::Vector3d p(rho * std::cos(theta), rho * std::sin(theta), z);
    double nearest = INFINITY, expected_u = 0.0;
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d a(r * std::cos(span * k / n), r * std::sin(span * k / n));
      const Eigen::Vector2d b(r * std::cos(span * (k + 1) / n), r * std::sin(span * (k + 1) / n));
      const Eigen::Vector2d q(p.x(), p.y());
      const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      const double d = (a + t * (b - a) - q).norm();
      if (d < nearest) nearest = d, expected_u = (k + t) / n;
    }
    const Eigen::Vector2d uv = surface.uv(surface.closest(p));
    ASSERT_NEAR(uv.x(), expected_u, 1e-12) << "trial " << trial;
    ASSERT_NEAR(uv.y(), z / h, 1e-12) << "trial " << trial;
    worst_smooth = std::max(worst_smooth, std::fabs(uv.x() - theta / span));
  }
  std::cout << "the facets' uv off the smooth cylinder's by at most " << worst_smooth * texels << " of a "
            << texels << "-texel texture's texels\n";
  EXPECT_LT(worst_smooth * texels, 0.5) << "the facets' uv is off the smooth surface's by " << worst_smooth * texels
                                        << " texels";
}

}  // namespace
}  // namespace bleedsim
