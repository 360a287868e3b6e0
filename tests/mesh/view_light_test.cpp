// The endoscope's view of a tissue mesh (core/mesh/view_render.h), how it is lit and seen, against
// closed forms worked out here on its own (view_geometry.h): the headlight's closed form at a plane's
// centre, the smooth normal as the corners' area-weighted normals interpolated, supersampling
// averaged in linear light, bad cameras refused by name, and the turbinate seen from an endoscope,
// its coverage the same as a ray cast's. Where its triangles land: view_render_test.cpp.
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
#include "tests/mesh/view_geometry.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

using namespace test;

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
  Image texture = load_tissue_png({test::source_dir() + "/scenarios/textures/mucosa-200x150.png", "texture"}, 200, 150);
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
