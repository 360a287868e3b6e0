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
