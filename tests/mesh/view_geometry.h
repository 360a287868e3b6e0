#pragma once
// What the tests of the endoscope's view of a tissue mesh share, worked out on their own rather
// than from the renderer: sRGB's transfer function, a textbook pinhole's rays, parallelograms and
// where a ray meets them, solid textures, unlit light and a camera looking at a point.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "core/io/mesh_obj.h"
#include "core/io/tissue_png.h"
#include "core/mesh/view_render.h"

namespace bleedsim::test {

// IEC 61966-2-1: an sRGB code value c ∈ [0, 1] as linear light.
inline double linear_from_code(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

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
inline TissueMesh parallelogram(const Eigen::Vector3d& origin, const Eigen::Vector3d& U, const Eigen::Vector3d& V,
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
inline Eigen::Vector3d ray_plane(const Ray& ray, const Eigen::Vector3d& origin, const Eigen::Vector3d& U,
                          const Eigen::Vector3d& V) {
  Eigen::Matrix3d m;
  m << U, V, -ray.direction;
  return m.fullPivLu().solve(ray.origin - origin);
}

inline Image solid_texture(int width, int height, const std::function<std::array<std::uint8_t, 3>(int, int)>& colour) {
  Image t{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4)};
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const auto c = colour(i, j);
      std::uint8_t* p = t.rgba.data() + (std::size_t(j) * width + i) * 4;
      p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
    }
  return t;
}

inline const std::uint8_t* pixel(const Image& image, int x, int y) {
  return image.rgba.data() + (std::size_t(y) * image.width + x) * 4;
}

// Light that shows the texture as it is: no shading (ambient 1) and no falloff, one sample a pixel.
inline ViewLight unlit() {
  ViewLight light;
  light.ambient = 1.0;
  light.falloff_mm = 0.0;
  light.samples_per_axis = 1;
  return light;
}

inline ViewCamera camera_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& look_at, int width, int height, double fov) {
  ViewCamera c;
  c.eye_mm = eye;
  c.look_at_mm = look_at;
  c.width_px = width;
  c.height_px = height;
  c.fov_y_deg = fov;
  return c;
}
}  // namespace bleedsim::test
