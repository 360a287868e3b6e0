// The surface maps baked from a tissue mesh (core/mesh/surface_bake.h): the flat panel at its own
// size is the identity to the bit; a cylinder's texels carry its facets' closed-form stretch and
// gravity; texel areas add up to the mesh's area; texels no triangle covers are off the surface.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "core/io/mesh_obj.h"
#include "core/mesh/surface_bake.h"
#include "core/physics/surface.h"
#include "tests/mesh/meshes_in_code.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

constexpr int F = kSurfaceFrameChannels;
constexpr int G = kSurfaceGravityChannels;

TEST(SurfaceBake, TheFlatPanelAtItsOwnSizeIsTheIdentity) {
  // The default scene's panel, as the shipped OBJ and as built in code, placed under the stylus.
  const TexturePanel panel{64, 48, 32.0, 24.0};
  MeshPlacement at;
  at.position_mm = Eigen::Vector3d(0, 0, 120);
  for (const TissueMesh& mesh : {load_tissue_mesh(test::source_dir() + "/scenarios/meshes/flat-panel.obj"),
                                 test::flat_panel_mesh(32.0, 24.0)}) {
    const SurfaceMaps maps = bake_surface_maps(placed(mesh, at), panel, Eigen::Vector3d(300.0, -1000.0, 0.0));
    ASSERT_EQ(maps.covered, std::size_t(64 * 48));
    for (std::size_t t = 0; t < maps.covered; ++t) {
      // Exactly: these are what make a flat mesh's run the flat panel's, bit for bit.
      ASSERT_EQ(maps.frame[F * t], 1.0f) << t;
      ASSERT_EQ(maps.frame[F * t + 1], 0.0f) << t;
      ASSERT_EQ(maps.frame[F * t + 2], 1.0f) << t;
      ASSERT_EQ(maps.frame[F * t + 3], 1.0f) << t;
      ASSERT_EQ(maps.gravity[G * t], 300.0f) << t;      // device +x is the panel's +x ...
      ASSERT_EQ(maps.gravity[G * t + 1], 1000.0f) << t;  // ... and device −y the panel's +y
    }
    const PanelStretch s = panel_stretch(mesh, panel);
    EXPECT_EQ(s.least, 1.0);
    EXPECT_EQ(s.greatest, 1.0);
  }
}

TEST(SurfaceBake, ACylindersTexelsCarryTheirFacetsStretchAndGravity) {
  // A cylinder patch (axis z) of radius r over `span` rad, n facets, on a W × H mm panel of
  // 200 × 100 px: facet k's panel→surface map is diagonal in its own frame, with
  //   a = chord / (W/n) = 2r·sin(δ/2)·n / W  (δ = span/n)   and   c = h / H,
  // and gravity g = (0, −g, 0) along it has components (g·ê_θ, g·ê_z) = (−g·cos θ_k, 0), θ_k the
  // facet's middle angle (its chord's direction is (−sin θ_k, cos θ_k, 0)). A texel belongs to the
  // facet whose u-range holds its centre. Bound: each value is a float rounding of a double
  // computation, within 2⁻²³ relative (and b within that of a, its exact value being 0).
  const double r = 5.0, span = 2.0, h = 6.0, W = 20.0, H = 8.0, g = 1000.0;
  const int n = 40, m = 3;
  const TexturePanel panel{200, 100, W, H};
  const SurfaceMaps maps = bake_surface_maps(test::cylinder_patch(r, span, h, n, m), panel, Eigen::Vector3d(0, -g, 0));
  ASSERT_EQ(maps.covered, std::size_t(200 * 100));
  const double delta = span / n, c = h / H, a = 2.0 * r * std::sin(delta / 2.0) * n / W;
  const double tolerance = 2.0 * std::ldexp(1.0, -23);
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 200; ++i) {
      const std::size_t t = std::size_t(j) * 200 + i;
      const int facet = int((i + 0.5) / 200.0 * n);
      const double theta = (facet + 0.5) * delta;
      ASSERT_NEAR(maps.frame[F * t], a, tolerance * a) << i << ", " << j;
      ASSERT_NEAR(maps.frame[F * t + 1], 0.0, tolerance * a) << i << ", " << j;
      ASSERT_NEAR(maps.frame[F * t + 2], c, tolerance * c) << i << ", " << j;
      ASSERT_NEAR(maps.gravity[G * t], -g * std::cos(theta), tolerance * g) << i << ", " << j;
      ASSERT_NEAR(maps.gravity[G * t + 1], 0.0, tolerance * g) << i << ", " << j;
    }
  const PanelStretch s = panel_stretch(test::cylinder_patch(r, span, h, n, m), panel);
  EXPECT_NEAR(s.least, std::min(a, c), 1e-12);
  EXPECT_NEAR(s.greatest, std::max(a, c), 1e-12);
}

// Σ over covered texels of det J × the pixel's panel area, against Σ of the triangles' areas.
double texel_area_mm2(const SurfaceMaps& maps, const TexturePanel& panel) {
  const double pixel_mm2 = panel.width_mm / panel.width_px * (panel.height_mm / panel.height_px);
  double sum = 0.0;
  for (std::size_t t = 0; t < std::size_t(maps.width) * maps.height; ++t)
    if (maps.frame[F * t + 3] != 0.0f) sum += double(maps.frame[F * t]) * maps.frame[F * t + 2] * pixel_mm2;
  return sum;
}

TEST(SurfaceBake, TexelAreasAddUpToTheTrianglesAreas) {
  // Each texel stands for its triangle's stretch over one pixel, so the texels of a triangle add up
  // to its area but for the texels its edges cut (their centres fall one side or the other). Across
  // an edge between two triangles those miscounts cancel but for the difference of the two
  // stretches; along the chart's border (here the texture's own edge) there are none. So the total
  // is off by at most (texels along inner edges) × (the largest stretch step between neighbours) ×
  // a pixel, well under the 1 % the issue asks on the turbinate, whose neighbours differ little.
  // At 640 × 480 its quads (10 × 20 texels) end on texel edges and only the diagonals cut texels;
  // at 333 × 251 every edge does.
  const TissueMesh mesh = load_tissue_mesh(test::source_dir() + "/scenarios/meshes/turbinate.obj");
  const double area = mesh.area_mm2();
  for (const TexturePanel& panel : {TexturePanel{640, 480, 40.0, 30.0}, TexturePanel{333, 251, 40.0, 30.0}}) {
    const SurfaceMaps maps = bake_surface_maps(mesh, panel, Eigen::Vector3d(0, -1000, 0));
    EXPECT_EQ(maps.covered, std::size_t(panel.width_px) * panel.height_px);
    const double texels = texel_area_mm2(maps, panel), error = std::abs(texels - area) / area;
    std::cout << "turbinate " << panel.width_px << " x " << panel.height_px << ": texels " << texels
              << " mm², triangles " << area << " mm², relative error " << error << "\n";
    EXPECT_LT(error, 0.01);
  }
}

TEST(SurfaceBake, TexelsNoTriangleCoversAreOffTheSurface) {
  // One triangle over the lower-left half of the uv square, (0,0), (0,1), (1,1): a texel centre
  // (u, v) is in it when u ≤ v. The rest are off the surface and borrow its frame and gravity.
  TissueMesh mesh;
  mesh.positions = {{0, 0, 0}, {0, -10, 0}, {20, -10, 0}};
  mesh.uvs = {{0, 0}, {0, 1}, {1, 1}};
  mesh.triangles = {{{0, 1, 2}, {0, 1, 2}}};
  const TexturePanel panel{30, 20, 20.0, 10.0};
  const SurfaceMaps maps = bake_surface_maps(mesh, panel, Eigen::Vector3d(0, -1000, 0));
  std::size_t expected = 0;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 30; ++i) {
      const std::size_t t = std::size_t(j) * 30 + i;
      const bool inside = (i + 0.5) / 30.0 <= (j + 0.5) / 20.0;
      expected += inside;
      EXPECT_EQ(maps.frame[F * t + 3], inside ? 1.0f : 0.0f) << i << ", " << j;
      EXPECT_EQ(maps.frame[F * t], 1.0f);
      EXPECT_EQ(maps.frame[F * t + 2], 1.0f);
      EXPECT_EQ(maps.gravity[G * t + 1], 1000.0f);
    }
  EXPECT_EQ(maps.covered, expected);
  // A mesh whose uvs hold no texel centre covers nothing: refused.
  mesh.uvs = {{0, 0}, {0, 0.01}, {0.01, 0.01}};
  EXPECT_THROW(bake_surface_maps(mesh, panel, Eigen::Vector3d(0, -1000, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace bleedsim
