// The endoscope's view of a tissue mesh (core/mesh/view_render.h), where its triangles land, against
// geometry worked out here on its own (view_geometry.h): a pinhole's rays through the pixel centres
// meet planes at a closed-form uv (head-on and tilted, where the screen's affine uv would be texels
// off); the outward side reads the texture the right way round; the nearer of two triangles shows,
// whatever their order; a triangle reaching behind the tip draws only its part in front; triangles
// sharing edges cover each sample once. Its light, its cameras and the turbinate:
// view_light_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <Eigen/Dense>

#include "core/io/mesh_obj.h"
#include "core/io/tissue_png.h"
#include "core/mesh/view_render.h"
#include "tests/mesh/view_geometry.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

using namespace test;

// A 40 × 30 mm rectangle centred on the origin, u along x and v down y, seen from 40 mm on the z axis
// head-on and then turned 60° about the x axis (its bottom away from the scope: depths 27 to 53 mm).
// At every covered pixel the renderer's uv is the ray–plane intersection's: exact but for rounding,
// 10⁻⁹ (a few dozen double operations on numbers of order 10², conditioned by 1/cos 60°, give
// 10⁻¹³). A gradient texture (red = column, green = row; 256 texels a side) unlit shows the uv: the
// bilinear filter mixes the two texels around x = 256 u − ½ in linear light, and rounding the mix to
// a byte gives one of those two (sRGB decoding and encoding are monotonic, and the byte boundary
// between two codes lies between their linear values), so |red − x| ≤ 1 (x clamped to [0, 255]
// at the edges, where both texels are the edge's). Tilted, the screen's affine uv — what a
// rasteriser without the division by depth would give — is off by more than that, so this tells the
// two apart.
TEST(ViewRender, PerspectiveUvIsTheRayPlaneIntersections) {
  const ViewCamera camera = camera_at({0, 0, 40}, {0, 0, 0}, 161, 121, 60.0);
  const Pinhole pinhole(camera);
  const Image gradient =
      solid_texture(256, 256, [](int i, int j) { return std::array<std::uint8_t, 3>{std::uint8_t(i), std::uint8_t(j), 0}; });
  for (const double tilt_deg : {0.0, 60.0}) {
    const double tilt = tilt_deg * M_PI / 180.0;
    const Eigen::Vector3d U(40, 0, 0), V = 30.0 * Eigen::Vector3d(0, -std::cos(tilt), -std::sin(tilt));
    const Eigen::Vector3d origin = -0.5 * U - 0.5 * V;
    const TissueMesh mesh = parallelogram(origin, U, V);
    const ViewSamples samples = rasterise_view(mesh, camera);
    const Image image = render_view(mesh, gradient, camera, unlit());
    int covered = 0;
    double worst_uv = 0.0, worst_byte = 0.0, worst_affine_texels = 0.0;
    for (int y = 0; y < camera.height_px; ++y)
      for (int x = 0; x < camera.width_px; ++x) {
        const std::size_t at = std::size_t(y) * samples.width + x;
        const Eigen::Vector3d hit = ray_plane(pinhole.ray(x + 0.5, y + 0.5), origin, U, V);
        const double margin = std::min({hit.x(), 1 - hit.x(), hit.y(), 1 - hit.y()});
        if (std::fabs(margin) < 1e-9) continue;  // on the rectangle's outline: either is right
        ASSERT_EQ(samples.triangle[at] >= 0, margin > 0) << "tilt " << tilt_deg << ", pixel " << x << ", " << y;
        if (margin < 0) {
          ASSERT_EQ(samples.coverage[at], 0);
          continue;
        }
        ++covered;
        ASSERT_EQ(samples.coverage[at], 1) << "tilt " << tilt_deg << ", pixel " << x << ", " << y;
        worst_uv = std::max(worst_uv, (samples.uv[at] - hit.head<2>()).cwiseAbs().maxCoeff());
        ASSERT_NEAR(samples.depth_mm[at], hit.z(), 1e-9);
        // The texture, through the bytes.
        for (int k = 0; k < 2; ++k) {
          const double expected = std::clamp(256.0 * hit[k] - 0.5, 0.0, 255.0);
          worst_byte = std::max(worst_byte, std::fabs(pixel(image, x, y)[k] - expected));
        }
        // What the screen's affine interpolation over the pixel's triangle would give.
        const auto& c = mesh.triangles[samples.triangle[at]].corner;
        const Eigen::Vector2d a = pinhole.project(mesh.positions[c[0]]), b = pinhole.project(mesh.positions[c[1]]),
                              d = pinhole.project(mesh.positions[c[2]]);
        Eigen::Matrix2d m;
        m << b - a, d - a;
        const Eigen::Vector2d w = m.inverse() * (Eigen::Vector2d(x + 0.5, y + 0.5) - a);
        const Eigen::Vector2d affine = (1 - w.x() - w.y()) * mesh.uvs[c[0]] + w.x() * mesh.uvs[c[1]] + w.y() * mesh.uvs[c[2]];
        worst_affine_texels = std::max(worst_affine_texels, 256.0 * (affine - hit.head<2>()).cwiseAbs().maxCoeff());
      }
    std::cout << "tilt " << tilt_deg << "°: " << covered << " pixels; uv off the ray's by " << worst_uv
              << ", the bytes off 256 uv − ½ by " << worst_byte << "; affine uv would be off by "
              << worst_affine_texels << " texels\n";
    EXPECT_GT(covered, 1000);
    EXPECT_LT(worst_uv, 1e-9);
    EXPECT_LE(worst_byte, 1.0 + 1e-9);
    if (tilt_deg > 0) {
      EXPECT_GT(worst_affine_texels, 2.0) << "the tilted case would not tell affine uv from perspective";
    }
  }
}

// The flat panel's outward normal is +z (towards the user), though its triangles wind clockwise
// seen from there; seen from +z its texture reads the right way round: the texture's top-left
// quadrant top left, its top-right top right, its bottom-left bottom left.
TEST(ViewRender, TheOutwardSideSeesTheTextureTheRightWayRound) {
  const TissueMesh panel = load_tissue_mesh(test::source_dir() + "/scenarios/meshes/flat-panel.obj");
  for (int t = 0; t < int(panel.triangles.size()); ++t) {
    const Eigen::Vector3d n = outward_normal(panel, t);
    EXPECT_GT(n.z(), 0.0) << "triangle " << t;
    EXPECT_NEAR(n.norm(), 2 * 0.5 * 32 * 24, 1e-9);  // twice the area: half the panel each
  }
  const std::array<std::uint8_t, 3> colours[4] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 0}};
  // Quadrants of 8 × 8 texels, so that a quadrant's middle is far from any mixing with another.
  const Image texture = solid_texture(16, 16, [&](int i, int j) { return colours[(j / 8) * 2 + i / 8]; });
  const Image image = render_view(panel, texture, camera_at({16, -12, 60}, {16, -12, 0}, 64, 48, 30.0), unlit());
  // Quarter points of the panel: (8, −6) mm is u = ¼, v = ¼, the middle of the top-left quadrant.
  const Pinhole pinhole(camera_at({16, -12, 60}, {16, -12, 0}, 64, 48, 30.0));
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const Eigen::Vector2d p = pinhole.project({8.0 + 16 * i, -6.0 - 12 * j, 0});
      const std::uint8_t* got = pixel(image, int(p.x()), int(p.y()));
      for (int k = 0; k < 3; ++k) EXPECT_EQ(got[k], colours[j * 2 + i][k]) << "texel " << i << ", " << j;
    }
}

// Two triangles overlapping in the middle of the view, one at z = 0 (red texels) and one 5 mm
// nearer the scope (blue texels): the nearer one's colour wins whichever is drawn first. Coplanar,
// the tie goes to the lower triangle. Unlit, colour = texture exactly: each triangle's uvs lie where
// the bilinear filter mixes only texels of its colour (u ≤ 0.3 reads texels 0 and 1 of a 4-texel
// row, u ≥ 0.7 texels 2 and 3), and a byte decoded and encoded again is itself.
TEST(ViewRender, TheNearerTriangleHidesTheFartherWhateverTheirOrder) {
  const ViewCamera camera = camera_at({0, 0, 50}, {0, 0, 0}, 33, 33, 40.0);
  const Image texture = solid_texture(4, 1, [](int i, int) {
    return i < 2 ? std::array<std::uint8_t, 3>{255, 0, 0} : std::array<std::uint8_t, 3>{0, 0, 255};
  });
  const auto make = [](double far_z, double near_z, bool near_first) {
    TissueMesh mesh;
    // The farther: wide, to the left and through the middle; the nearer: to the right and through it.
    mesh.positions = {{-10, -8, far_z}, {4, 0, far_z}, {-10, 8, far_z}, {10, -8, near_z}, {10, 8, near_z}, {-4, 0, near_z}};
    mesh.uvs = {{0.05, 0.1}, {0.3, 0.5}, {0.05, 0.9}, {0.95, 0.1}, {0.95, 0.9}, {0.7, 0.5}};
    const TissueMesh::Triangle far{{0, 1, 2}, {0, 1, 2}}, near{{3, 4, 5}, {3, 4, 5}};
    mesh.triangles = near_first ? std::vector<TissueMesh::Triangle>{near, far} : std::vector<TissueMesh::Triangle>{far, near};
    return mesh;
  };
  const std::array<std::uint8_t, 3> red{255, 0, 0}, blue{0, 0, 255};
  const auto colour_at = [&](const Image& image, int x, int y) {
    const std::uint8_t* p = pixel(image, x, y);
    return std::array<std::uint8_t, 3>{p[0], p[1], p[2]};
  };
  for (const bool near_first : {false, true}) {
    const Image image = render_view(make(0.0, 5.0, near_first), texture, camera, unlit());
    EXPECT_EQ(colour_at(image, 16, 16), blue) << "near first: " << near_first;  // both cover the centre
    EXPECT_EQ(colour_at(image, 8, 16), red) << "near first: " << near_first;    // only the farther
    EXPECT_EQ(colour_at(image, 24, 16), blue) << "near first: " << near_first;  // only the nearer
    // Coplanar: the lower triangle keeps the pixels both cover.
    const Image tie = render_view(make(0.0, 0.0, near_first), texture, camera, unlit());
    EXPECT_EQ(colour_at(tie, 16, 16), near_first ? blue : red) << "near first: " << near_first;
  }
}

// A floor 2 mm below a camera at the origin looking down −z (near plane 5 mm), a triangle with one,
// then two, corners behind the camera. A pixel's ray meets the floor at depth t = 2 / (−y_n) below
// the horizon (y_n the ray's downward slope) and never above it; the pixel is covered exactly when
// that point lies in the triangle and t ≥ 5 mm, and its uv is the floor's affine uv there. Pixels
// within 10⁻⁶ mm of an edge or the near plane are left out (either answer is right to rounding,
// 10⁻¹²). Nothing may wrap: a corner behind the camera projected naively lands above the horizon.
TEST(ViewRender, ATriangleReachingBehindTheCameraDrawsOnlyItsPartInFront) {
  ViewCamera camera = camera_at({0, 0, 0}, {0, 0, -1}, 101, 101, 90.0);
  camera.near_mm = 5.0;
  const Pinhole pinhole(camera);
  const auto uv_at = [](const Eigen::Vector3d& p) { return Eigen::Vector2d((p.x() + 30) / 60, (p.z() + 60) / 100); };
  const std::vector<std::array<Eigen::Vector3d, 3>> cases = {
      {Eigen::Vector3d(-30, -2, -60), Eigen::Vector3d(30, -2, -60), Eigen::Vector3d(0, -2, 40)},    // one behind
      {Eigen::Vector3d(0, -2, -60), Eigen::Vector3d(-30, -2, 40), Eigen::Vector3d(30, -2, 40)}};   // two behind
  for (std::size_t k = 0; k < cases.size(); ++k) {
    TissueMesh mesh;
    for (const Eigen::Vector3d& p : cases[k]) {
      mesh.positions.push_back(p);
      mesh.uvs.push_back(uv_at(p));
    }
    mesh.triangles = {{{0, 1, 2}, {0, 1, 2}}};
    const ViewSamples samples = rasterise_view(mesh, camera);
    int expected_covered = 0, covered_above_horizon = 0;
    for (int y = 0; y < camera.height_px; ++y)
      for (int x = 0; x < camera.width_px; ++x) {
        const std::size_t at = std::size_t(y) * samples.width + x;
        if (y + 0.5 < 0.5 * camera.height_px) covered_above_horizon += samples.coverage[at];
        const Ray ray = pinhole.ray(x + 0.5, y + 0.5);
        bool inside = false;
        if (ray.direction.y() < 0) {
          const double t = -2.0 / ray.direction.y();
          const Eigen::Vector3d q = t * ray.direction;
          // Signed distances to the triangle's edges in the floor's plane (x, z), positive inside.
          double margin = t - camera.near_mm;
          const Eigen::Vector2d a(cases[k][0].x(), cases[k][0].z()), b(cases[k][1].x(), cases[k][1].z()),
              c(cases[k][2].x(), cases[k][2].z()), p(q.x(), q.z());
          const auto side = [](const Eigen::Vector2d& from, const Eigen::Vector2d& to, const Eigen::Vector2d& other,
                               const Eigen::Vector2d& at) {
            const Eigen::Vector2d e = to - from;
            const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
            return cross(e, at - from) / e.norm() * (cross(e, other - from) > 0 ? 1 : -1);
          };
          margin = std::min({margin, side(a, b, c, p), side(b, c, a, p), side(c, a, b, p)});
          if (std::fabs(margin) < 1e-6) continue;
          inside = margin > 0;
          if (inside) {
            ASSERT_NEAR(samples.depth_mm[at], t, 1e-9) << "case " << k << ", pixel " << x << ", " << y;
            ASSERT_LT((samples.uv[at] - uv_at(q)).cwiseAbs().maxCoeff(), 1e-9) << "case " << k;
          }
        }
        expected_covered += inside;
        ASSERT_EQ(samples.coverage[at], inside ? 1 : 0) << "case " << k << ", pixel " << x << ", " << y;
      }
    std::cout << "case " << k << ": " << expected_covered << " pixels in front of the near plane\n";
    EXPECT_GT(expected_covered, 200) << "case " << k;  // the part in front is drawn, not dropped
    EXPECT_EQ(covered_above_horizon, 0) << "case " << k;
  }
}

// Triangles sharing edges cover each sample of their union once. A diamond of four triangles around
// a vertex on the view axis, in a 63 × 47 view at one sample a pixel: the axis projects to the
// image's centre (31.5, 23.5), a pixel centre, so the shared edges (the diamond's diagonals) run
// exactly through a column and a row of pixel centres, and the top-left rule alone decides those.
// Then a tilted 4 × 3 grid (24 triangles, shared edges at every angle) at 2 × 2 samples a pixel.
// Samples within 10⁻⁹ (pixels, or uv) of the union's outline are left out: either answer is right.
TEST(ViewRender, TrianglesSharingAnEdgeCoverEachSampleOnce) {
  {
    const ViewCamera camera = camera_at({0, 0, 30}, {0, 0, 0}, 63, 47, 60.0);
    const Pinhole pinhole(camera);
    const double r = 10.0;
    TissueMesh mesh;
    mesh.positions = {{0, 0, 0}, {r, 0, 0}, {0, r, 0}, {-r, 0, 0}, {0, -r, 0}};
    for (const Eigen::Vector3d& p : mesh.positions) mesh.uvs.emplace_back(0.5 + p.x() / (2 * r), 0.5 - p.y() / (2 * r));
    for (int k = 0; k < 4; ++k) mesh.triangles.push_back({{0, 1 + k, 1 + (k + 1) % 4}, {0, 1 + k, 1 + (k + 1) % 4}});
    const ViewSamples samples = rasterise_view(mesh, camera);
    const double reach = pinhole.project({r, 0, 0}).x() - 0.5 * camera.width_px;  // the diamond's, in pixels
    int on_shared_edges = 0, inside = 0;
    for (int y = 0; y < camera.height_px; ++y)
      for (int x = 0; x < camera.width_px; ++x) {
        const double dx = x + 0.5 - 0.5 * camera.width_px, dy = y + 0.5 - 0.5 * camera.height_px;
        const double margin = reach - std::fabs(dx) - std::fabs(dy);
        if (std::fabs(margin) < 1e-9) continue;
        const int count = samples.coverage[std::size_t(y) * samples.width + x];
        ASSERT_EQ(count, margin > 0 ? 1 : 0) << "pixel " << x << ", " << y;
        inside += margin > 0;
        on_shared_edges += margin > 0 && (dx == 0 || dy == 0);
      }
    std::cout << "diamond: " << inside << " pixels, " << on_shared_edges << " of them exactly on a shared edge\n";
    // The diagonals through the centre: 2 ⌊reach⌋ + 1 pixel centres each, the centre on both.
    EXPECT_EQ(on_shared_edges, 2 * (2 * int(std::floor(reach)) + 1) - 1);
  }
  {
    const ViewCamera camera = camera_at({3, 2, 35}, {0, 0, 0}, 120, 90, 60.0);
    const Pinhole pinhole(camera);
    const Eigen::Vector3d U(30, 4, -8), V(-5, -24, -12), origin = -0.5 * U - 0.5 * V;
    const TissueMesh mesh = parallelogram(origin, U, V, 4, 3);
    const int n = 2;
    const ViewSamples samples = rasterise_view(mesh, camera, n);
    int inside = 0;
    for (int y = 0; y < samples.height; ++y)
      for (int x = 0; x < samples.width; ++x) {
        const Eigen::Vector3d hit = ray_plane(pinhole.ray((x + 0.5) / n, (y + 0.5) / n), origin, U, V);
        const double margin = std::min({hit.x(), 1 - hit.x(), hit.y(), 1 - hit.y()});
        if (std::fabs(margin) < 1e-9) continue;
        ASSERT_EQ(samples.coverage[std::size_t(y) * samples.width + x], margin > 0 ? 1 : 0)
            << "sample " << x << ", " << y;
        inside += margin > 0;
      }
    EXPECT_GT(inside, 5000);
  }
}

}  // namespace
}  // namespace bleedsim
