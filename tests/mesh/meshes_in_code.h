#pragma once
// Tissue meshes built in code from a parametric surface: the flat panel at any size, patches of a
// cylinder. Their uv is the parameter, so every closed form a test needs is the surface's own.
#include <cmath>

#include "core/mesh/tissue_mesh.h"

namespace bleedsim::test {

// The surface point(u, v), u, v ∈ [0, 1], as n × m quads of two triangles each, uv = (u, v).
template <class Point>
TissueMesh parametric_mesh(int n, int m, Point point) {
  TissueMesh mesh;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = double(i) / n, v = double(j) / m;
      mesh.positions.push_back(point(u, v));
      mesh.uvs.emplace_back(u, v);
    }
  const auto at = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      mesh.triangles.push_back({{a, b, c}, {a, b, c}});
      mesh.triangles.push_back({{a, c, d}, {a, c, d}});
    }
  return mesh;
}

// The flat panel of a scene, width × height mm, in the plane z = 0 as the device faces it: x right,
// y up, so the panel's y (down the texture) is the device's −y (scenarios/meshes/flat-panel.obj).
inline TissueMesh flat_panel_mesh(double width_mm, double height_mm) {
  return parametric_mesh(1, 1, [&](double u, double v) { return Eigen::Vector3d(u * width_mm, -v * height_mm, 0.0); });
}

// A cylinder patch of radius r over `span` radians and height h: n facets around, m rows up,
// uv = (θ / span, z / h).
inline TissueMesh cylinder_patch(double r, double span, double h, int n, int m) {
  return parametric_mesh(n, m, [&](double u, double v) {
    return Eigen::Vector3d(r * std::cos(span * u), r * std::sin(span * u), h * v);
  });
}

}  // namespace bleedsim::test
