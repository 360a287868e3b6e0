// The endoscope's view of a tissue mesh (core/mesh/view_render.h), against geometry worked out here
// on its own: a pinhole's rays through the pixel centres meet planes at a closed-form uv (head-on
// and tilted, where the screen's affine uv would be texels off); the nearer of two triangles shows,
// whatever their order; a triangle reaching behind the tip draws only its part in front; triangles
// sharing edges cover each sample once; the headlight's closed form at a plane's centre; bad cameras
// refused by name; and the turbinate seen from an endoscope, its coverage the same as a ray cast's.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/io/mesh_obj.h"
#include "core/io/png_writer.h"
#include "core/io/tissue_png.h"
#include "core/mesh/view_render.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

// IEC 61966-2-1: an sRGB code value c ∈ [0, 1] as linear light, and back.
double linear_from_code(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// A pinhole's ray through a point of the screen (pixels), worked out from the camera's fields as
// a textbook would: forward to look_at, right = forward × up, the image's up = right × forward, the
// screen at the focal length (H/2) / tan(fov/2) pixels. The direction's forward component is 1, so
// a hit's ray parameter is its depth.
struct Ray {
  Eigen::Vector3d origin, direction;
};
struct Pinhole {
  explicit Pinhole(const ViewCamera& c) : camera(c) {
    forward = (c.look_at_mm - c.eye_mm).normalized();
    right = forward.cross(c.up).normalized();
    up = right.cross(forward);
    focal = 0.5 * c.height_px / std::tan(c.fov_y_deg * M_PI / 360.0);
  }
  Ray ray(double x, double y) const {
    return {camera.eye_mm, forward + right * ((x - 0.5 * camera.width_px) / focal) -
                               up * ((y - 0.5 * camera.height_px) / focal)};
  }
  Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - camera.eye_mm;
    return {0.5 * camera.width_px + focal * d.dot(right) / d.dot(forward),
            0.5 * camera.height_px - focal * d.dot(up) / d.dot(forward)};
  }
  ViewCamera camera;
  Eigen::Vector3d forward, right, up;
  double focal;
};

// The parallelogram origin + u·U + v·V for (u, v) in the unit square, uv = (u, v), as two triangles;
// `rows` × `columns` quads when asked for more.
TissueMesh parallelogram(const Eigen::Vector3d& origin, const Eigen::Vector3d& U, const Eigen::Vector3d& V,
                         int columns = 1, int rows = 1) {
  TissueMesh mesh;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= columns; ++i) {
      const double u = double(i) / columns, v = double(j) / rows;
      mesh.positions.push_back(origin + u * U + v * V);
      mesh.uvs.emplace_back(u, v);
    }
  const auto at = [&](int i, int j) { return j * (columns + 1) + i; };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      mesh.triangles.push_back({{a, b, c}, {a, b, c}});
      mesh.triangles.push_back({{a, c, d}, {a, c, d}});
    }
  return mesh;
}

// Where a ray meets the plane origin + u·U + v·V: (u, v, ray parameter).
Eigen::Vector3d ray_plane(const Ray& ray, const Eigen::Vector3d& origin, const Eigen::Vector3d& U,
                          const Eigen::Vector3d& V) {
  Eigen::Matrix3d m;
  m << U, V, -ray.direction;
  return m.fullPivLu().solve(ray.origin - origin);
}

Image solid_texture(int width, int height, const std::function<std::array<std::uint8_t, 3>(int, int)>& colour) {
  Image t{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4)};
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const auto c = colour(i, j);
      std::uint8_t* p = t.rgba.data() + (std::size_t(j) * width + i) * 4;
      p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
    }
  return t;
}

const std::uint8_t* pixel(const Image& image, int x, int y) {
  return image.rgba.data() + (std::size_t(y) * image.width + x) * 4;
}

// Light that shows the texture as it is: no shading (ambient 1) and no falloff, one sample a pixel.
ViewLight unlit() {
  ViewLight light;
  light.ambient = 1.0;
  light.falloff_mm = 0.0;
  light.samples_per_axis = 1;
  return light;
}

ViewCamera camera_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& look_at, int width, int height, double fov) {
  ViewCamera c;
  c.eye_mm = eye;
  c.look_at_mm = look_at;
  c.width_px = width;
  c.height_px = height;
  c.fov_y_deg = fov;
  return c;
}

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

// A plane square to the view axis at d from the tip, a grey texture (sRGB byte 200): at the centre
// pixel the normal points at the tip, |n̂·l̂| = 1, and the pixel's linear value is
// L(200) · (a + (1 − a)) · 1 / (1 + (d / d0)²); turned by θ about the axis through that point,
// |n̂·l̂| = |cos θ| (past 90° the scope sees the plane's inner side, lit alike). The byte written
// is the sRGB code nearest that value: its linear value lies between those of the codes half a step
// either side (the tables are floats: 10⁻⁶ of slack).
TEST(ViewRender, TheHeadlightsClosedFormAtAPlanesCentre) {
  const Image grey = solid_texture(1, 1, [](int, int) { return std::array<std::uint8_t, 3>{200, 200, 200}; });
  struct Case {
    double distance, ambient, falloff, tilt_deg;
  };
  for (const Case& c : {Case{20, 0.3, 15, 0}, Case{20, 0.3, 0, 0}, Case{30, 0.0, 60, 0}, Case{20, 0.3, 15, 60},
                        Case{12, 0.6, 40, 75}, Case{20, 0.3, 15, 180}, Case{20, 0.0, 15, 240}}) {
    const double tilt = c.tilt_deg * M_PI / 180.0;
    const Eigen::Vector3d U(100, 0, 0), V = 100.0 * Eigen::Vector3d(0, -std::cos(tilt), -std::sin(tilt));
    const TissueMesh plane = parallelogram(-0.5 * U - 0.5 * V, U, V);
    ViewLight light;
    light.ambient = c.ambient;
    light.falloff_mm = c.falloff;
    light.samples_per_axis = 1;
    const Image image = render_view(plane, grey, camera_at({0, 0, c.distance}, {0, 0, 0}, 5, 5, 40.0), light);
    const double falloff = c.falloff > 0 ? 1.0 / (1.0 + std::pow(c.distance / c.falloff, 2)) : 1.0;
    const double expected = linear_from_code(200 / 255.0) * (c.ambient + (1 - c.ambient) * std::fabs(std::cos(tilt))) * falloff;
    for (int k = 0; k < 3; ++k) {
      const int byte = pixel(image, 2, 2)[k];
      EXPECT_LE(linear_from_code((byte - 0.5) / 255.0), expected * (1 + 1e-6))
          << "d " << c.distance << ", a " << c.ambient << ", d0 " << c.falloff << ", tilt " << c.tilt_deg;
      EXPECT_GE(linear_from_code((byte + 0.5) / 255.0), expected * (1 - 1e-6))
          << "d " << c.distance << ", a " << c.ambient << ", d0 " << c.falloff << ", tilt " << c.tilt_deg;
    }
  }
  // Nothing in view: every pixel is the background, to the byte.
  const Image empty = render_view(parallelogram({100, 100, 0}, {1, 0, 0}, {0, -1, 0}), grey,
                                  camera_at({0, 0, 20}, {0, 0, 0}, 8, 6, 40.0));
  const ViewLight defaults;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x)
      for (int k = 0; k < 3; ++k) ASSERT_EQ(pixel(empty, x, y)[k], defaults.background[k]);
}

// Möller–Trumbore: the ray parameter and the barycentric weights (1 − s − t, s, t) of triangle abc.
Eigen::Vector3d ray_triangle(const Ray& ray, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, p = ray.direction.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0) return {-1, -1, -1};
  const Eigen::Vector3d s = ray.origin - a, q = s.cross(e1);
  return {e2.dot(q) / det, s.dot(p) / det, ray.direction.dot(q) / det};
}

// The shading normal is smooth: a cylinder of radius 10 mm about the y axis in six 40° facets, lit
// unattenuated with no ambient light, seen along −z through a point a quarter of the way across the
// facet from 0° to 40°. Each corner's normal is the sum of its triangles' normals, each pointing
// away from the axis with a length of twice the triangle's area (worked out here from the corners);
// at the point they are interpolated by its barycentric weights, and the pixel's linear value is
// L(255) · |n̂ · l̂|, to the byte as above. The facet's own normal, 20° from the view there against
// the smooth normal's 10°, would be 5 % darker: about five codes.
TEST(ViewRender, TheSmoothNormalIsTheCornersAreaWeightedNormalsInterpolated) {
  const double r = 10.0, step = 40.0 * M_PI / 180.0;
  TissueMesh mesh;
  for (int j = 0; j < 2; ++j)
    for (int k = 0; k <= 6; ++k) {
      const double theta = (k - 3) * step;
      mesh.positions.emplace_back(r * std::sin(theta), j == 0 ? 20.0 : -20.0, r * std::cos(theta));
      mesh.uvs.emplace_back(k / 6.0, double(j));
    }
  for (int k = 0; k < 6; ++k) {
    const int a = k, b = k + 1, c = 7 + k + 1, d = 7 + k;
    mesh.triangles.push_back({{a, b, c}, {a, b, c}});
    mesh.triangles.push_back({{a, c, d}, {a, c, d}});
  }
  std::vector<Eigen::Vector3d> corner_normals(mesh.positions.size(), Eigen::Vector3d::Zero());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.positions[t.corner[0]], &b = mesh.positions[t.corner[1]], &c = mesh.positions[t.corner[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    if (n.dot(Eigen::Vector3d(centroid.x(), 0, centroid.z())) < 0) n = -n;
    for (int i : t.corner) corner_normals[i] += n;
  }
  const double x0 = 0.25 * r * std::sin(step);
  const ViewCamera camera = camera_at({x0, 0, 40}, {x0, 0, 0}, 5, 5, 30.0);
  const Ray ray = Pinhole(camera).ray(2.5, 2.5);
  Eigen::Vector3d normal = Eigen::Vector3d::Zero(), point = Eigen::Vector3d::Zero();
  double nearest = INFINITY;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d hit = ray_triangle(ray, mesh.positions[t.corner[0]], mesh.positions[t.corner[1]],
                                             mesh.positions[t.corner[2]]);
    const Eigen::Vector3d w(1 - hit.y() - hit.z(), hit.y(), hit.z());
    if (hit.x() <= 0 || w.minCoeff() < 0 || hit.x() >= nearest) continue;
    nearest = hit.x();
    point = ray.origin + hit.x() * ray.direction;
    normal = w[0] * corner_normals[t.corner[0]] + w[1] * corner_normals[t.corner[1]] + w[2] * corner_normals[t.corner[2]];
  }
  ASSERT_LT(nearest, INFINITY);
  ViewLight light = unlit();
  light.ambient = 0.0;
  const Image white = solid_texture(1, 1, [](int, int) { return std::array<std::uint8_t, 3>{255, 255, 255}; });
  const Image image = render_view(mesh, white, camera, light);
  const double expected = std::fabs(normal.normalized().dot((camera.eye_mm - point).normalized()));
  for (int k = 0; k < 3; ++k) {
    const int byte = pixel(image, 2, 2)[k];
    EXPECT_LE(linear_from_code((byte - 0.5) / 255.0), expected * (1 + 1e-6));
    EXPECT_GE(linear_from_code((byte + 0.5) / 255.0), expected * (1 - 1e-6));
  }
}

// Samples are averaged in linear light: a white plane whose edge runs down the view axis, in a view
// 7 pixels wide at 2 × 2 samples, covers exactly the left two samples of the middle column's pixels
// (the axis is that column's centre, the samples a quarter pixel either side). Those pixels are
// the sRGB code of (L(255) + L(background)) / 2 (half a byte, 10⁻⁶ slack, as above), about 188 —
// not the bytes' mean, 132.
TEST(ViewRender, SupersamplingAveragesInLinearLight) {
  const Image white = solid_texture(1, 1, [](int, int) { return std::array<std::uint8_t, 3>{255, 255, 255}; });
  const TissueMesh half = parallelogram({-20, 20, 0}, {20, 0, 0}, {0, -40, 0});
  ViewLight light = unlit();
  light.samples_per_axis = 2;
  const Image image = render_view(half, white, camera_at({0, 0, 30}, {0, 0, 0}, 7, 5, 40.0), light);
  for (int y = 0; y < 5; ++y)
    for (int k = 0; k < 3; ++k) {
      const double expected = 0.5 * (1.0 + linear_from_code(light.background[k] / 255.0));
      const int byte = pixel(image, 3, y)[k];
      EXPECT_LE(linear_from_code((byte - 0.5) / 255.0), expected * (1 + 1e-6)) << "row " << y;
      EXPECT_GE(linear_from_code((byte + 0.5) / 255.0), expected * (1 - 1e-6)) << "row " << y;
      EXPECT_EQ(pixel(image, 2, y)[k], 255);
      EXPECT_EQ(pixel(image, 4, y)[k], light.background[k]);
    }
}

// A degenerate camera, light, texture or mesh is refused with a message naming the problem.
TEST(ViewRender, BadCamerasAreRefusedByName) {
  const TissueMesh mesh = parallelogram({-1, 1, 0}, {2, 0, 0}, {0, -2, 0});
  const Image texture = solid_texture(1, 1, [](int, int) { return std::array<std::uint8_t, 3>{1, 2, 3}; });
  const ViewCamera good = camera_at({0, 0, 10}, {0, 0, 0}, 16, 12, 60.0);
  const auto refusal = [&](const ViewCamera& camera, const ViewLight& light, const Image& t, const TissueMesh& m) {
    try {
      render_view(m, t, camera, light);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  struct Case {
    std::function<void(ViewCamera&, ViewLight&, Image&, TissueMesh&)> spoil;
    std::string names;
  };
  const std::vector<Case> cases = {
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.look_at_mm = c.eye_mm; }, "the same point"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.up = {0, 0, -3}; }, "up [0, 0, -3] is parallel to the view direction"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.up = {0, 0, 0}; }, "up is the zero vector"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.fov_y_deg = 0; }, "fov_y_deg is 0;"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.fov_y_deg = 180; }, "fov_y_deg is 180;"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.fov_y_deg = NAN; }, "fov_y_deg is nan"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.width_px = 0; }, "width_px and height_px must be 1 to 16384"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.height_px = 16385; }, "16 x 16385 pixels"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.near_mm = 0; }, "near_mm is 0;"},
      {[](ViewCamera& c, ViewLight&, Image&, TissueMesh&) { c.eye_mm.x() = INFINITY; }, "must be finite"},
      {[](ViewCamera&, ViewLight& l, Image&, TissueMesh&) { l.ambient = 1.5; }, "ambient is 1.500000"},
      {[](ViewCamera&, ViewLight& l, Image&, TissueMesh&) { l.falloff_mm = -1; }, "falloff_mm is -1.000000"},
      {[](ViewCamera&, ViewLight& l, Image&, TissueMesh&) { l.samples_per_axis = 17; }, "samples_per_axis is 17"},
      {[](ViewCamera&, ViewLight&, Image& t, TissueMesh&) { t.rgba.pop_back(); }, "the texture is 1 x 1 with 3 bytes"},
      {[](ViewCamera&, ViewLight&, Image&, TissueMesh& m) { m.triangles[1].corner[2] = 9; }, "triangle 1 names a position"},
      {[](ViewCamera&, ViewLight&, Image&, TissueMesh& m) { m.uvs[3].x() = NAN; }, "texture coordinate 3 is not finite"},
  };
  EXPECT_EQ(refusal(good, ViewLight{}, texture, mesh), "(accepted)");
  for (const Case& c : cases) {
    ViewCamera camera = good;
    ViewLight light;
    Image t = texture;
    TissueMesh m = mesh;
    c.spoil(camera, light, t, m);
    const std::string message = refusal(camera, light, t, m);
    EXPECT_NE(message.find(c.names), std::string::npos) << "expected \"" << c.names << "\" in: " << message;
  }
  // The debug rasteriser checks the camera alike.
  ViewCamera looks_nowhere = good;
  looks_nowhere.look_at_mm = looks_nowhere.eye_mm;
  EXPECT_THROW(rasterise_view(mesh, looks_nowhere), std::invalid_argument);
}

// The turbinate seen as an endoscope would: 25 mm in front of (towards +z from) the middle of its
// bounding box, looking at it, 90° vertically. Its bounding box — 40 mm long, 20 mm high — then fits
// the view: every corner projects inside the image. At 128 × 96 pixels, one sample each, the
// rasteriser covers a pixel exactly when a ray cast through its centre against every triangle hits
// one, and shows the ray's nearest triangle (pixels within 10⁻⁹ of a triangle's edge, in its
// barycentric weights, or with two hits within 10⁻⁹ mm, are left out). Then the 640 × 480 view with
// the mucosa texture and a painted stain, timed, written for a person to look at
// (test_output/view_render/turbinate.png in the build tree): its tissue is where the rasteriser's
// samples are.
TEST(ViewRender, TheTurbinateFromAnEndoscope) {
  const TissueMesh mesh = load_tissue_mesh(test::source_dir() + "/scenarios/meshes/turbinate.obj");
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : mesh.positions) box.extend(p);
  ViewCamera camera = camera_at(box.center() + Eigen::Vector3d(0, 0, 25), box.center(), 128, 96, 90.0);
  {
    const Pinhole pinhole(camera);
    for (const Eigen::Vector3d& p : mesh.positions) {
      const Eigen::Vector2d s = pinhole.project(p);
      ASSERT_GT((p - camera.eye_mm).dot(pinhole.forward), camera.near_mm);
      ASSERT_TRUE(s.x() > 0 && s.x() < camera.width_px && s.y() > 0 && s.y() < camera.height_px)
          << "a corner outside the view at " << s.transpose();
    }
    const ViewSamples samples = rasterise_view(mesh, camera);
    int compared = 0, covered = 0;
    for (int y = 0; y < camera.height_px; ++y)
      for (int x = 0; x < camera.width_px; ++x) {
        const Ray ray = pinhole.ray(x + 0.5, y + 0.5);
        double nearest = INFINITY, second = INFINITY;
        int nearest_triangle = -1;
        bool ambiguous = false;
        for (int t = 0; t < int(mesh.triangles.size()) && !ambiguous; ++t) {
          const auto& c = mesh.triangles[t].corner;
          const Eigen::Vector3d hit = ray_triangle(ray, mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]);
          const double margin = std::min({1 - hit.y() - hit.z(), hit.y(), hit.z()});
          if (hit.x() <= 0 || margin < -1e-9) continue;
          if (margin < 1e-9) ambiguous = true;
          if (hit.x() < nearest) second = nearest, nearest = hit.x(), nearest_triangle = t;
          else second = std::min(second, hit.x());
        }
        if (ambiguous || second - nearest < 1e-9) continue;
        ++compared;
        covered += nearest_triangle >= 0;
        ASSERT_EQ(samples.triangle[std::size_t(y) * samples.width + x], nearest_triangle) << "pixel " << x << ", " << y;
      }
    std::cout << "turbinate: " << covered << " of " << compared << " pixels compared with a ray cast are tissue\n";
    EXPECT_GT(compared, camera.width_px * camera.height_px * 9 / 10);
  }

  // The mucosa texture, with a stain of blood (a Gaussian of dark red) across the middle.
  Image texture = load_tissue_png(test::source_dir() + "/scenarios/textures/mucosa-200x150.png", 200, 150, {}, "texture");
  for (int j = 0; j < texture.height; ++j)
    for (int i = 0; i < texture.width; ++i) {
      const double u = (i + 0.5) / texture.width, v = (j + 0.5) / texture.height;
      const double w = 0.85 * std::exp(-(std::pow((u - 0.45) / 0.08, 2) + std::pow((v - 0.5) / 0.15, 2)));
      const std::uint8_t blood[3] = {110, 12, 14};
      std::uint8_t* p = texture.rgba.data() + (std::size_t(j) * texture.width + i) * 4;
      for (int k = 0; k < 3; ++k) p[k] = std::uint8_t(std::lround((1 - w) * p[k] + w * blood[k]));
    }
  camera.width_px = 640;
  camera.height_px = 480;
  const auto start = std::chrono::steady_clock::now();
  const Image image = render_view(mesh, texture, camera);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::filesystem::path folder = std::filesystem::path(test::binary_dir()) / "test_output" / "view_render";
  std::filesystem::create_directories(folder);
  write_png_rgba((folder / "turbinate.png").string(), image.width, image.height, image.rgba.data());
  // A pixel none of whose 2 × 2 samples is covered is the background; one all of whose samples are
  // is not: the dimmest tissue (the stain's red byte, 125, at the ambient light alone and the
  // falloff of the farthest corner, 33 mm away) is ten times the background's red in linear light.
  const ViewSamples samples = rasterise_view(mesh, camera, 2);
  const ViewLight defaults;
  int tissue = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      int covered = 0;
      for (int k = 0; k < 4; ++k) covered += samples.triangle[std::size_t(2 * y + k / 2) * samples.width + 2 * x + k % 2] >= 0;
      const bool background = std::equal(defaults.background.begin(), defaults.background.end(), pixel(image, x, y));
      tissue += !background;
      if (covered == 0) {
        ASSERT_TRUE(background) << "pixel " << x << ", " << y;
      }
      if (covered == 4) {
        ASSERT_FALSE(background) << "pixel " << x << ", " << y;
      }
    }
  std::cout << "turbinate at 640 x 480, 2 x 2 samples a pixel, " << mesh.triangles.size() << " triangles: "
            << seconds * 1e3 << " ms; " << tissue << " pixels of tissue; " << (folder / "turbinate.png").string() << "\n";
}

}  // namespace
}  // namespace bleedsim
