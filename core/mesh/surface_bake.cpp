#include "core/mesh/surface_bake.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>

#include "core/physics/surface.h"

namespace bleedsim {
namespace {

// A triangle's map from panel to surface mm: J = dP · dX⁻¹, from its corners' edges in space (dP,
// 3 × 2) and on the panel (dX, 2 × 2; its uvs have area, which the mesh's check makes sure of).
Eigen::Matrix<double, 3, 2> panel_to_surface(const TissueMesh& mesh, const TissueMesh::Triangle& t,
                                             const TexturePanel& panel) {
  const auto at_panel = [&](int k) {
    const Eigen::Vector2d& uv = mesh.uvs[t.uv[k]];
    return Eigen::Vector2d(uv.x() * panel.width_mm, uv.y() * panel.height_mm);
  };
  Eigen::Matrix<double, 3, 2> dp;
  dp << mesh.positions[t.corner[1]] - mesh.positions[t.corner[0]], mesh.positions[t.corner[2]] - mesh.positions[t.corner[0]];
  Eigen::Matrix2d dx;
  dx << at_panel(1) - at_panel(0), at_panel(2) - at_panel(0);
  return dp * dx.inverse();
}

// J in the tangent plane's frame whose first axis lies along ∂P/∂x (core/physics/surface.h), and
// the tangential gravity in that frame.
struct TexelValues {
  double a, b, c, gx, gy;
};

TexelValues frame_values(const Eigen::Matrix<double, 3, 2>& j, const Eigen::Vector3d& gravity) {
  const Eigen::Vector3d along_x = j.col(0), along_y = j.col(1);
  const double a = along_x.norm();
  const Eigen::Vector3d e1 = along_x / a;
  const double b = along_y.dot(e1);
  const Eigen::Vector3d rest = along_y - b * e1;
  const double c = rest.norm();
  const Eigen::Vector3d e2 = rest / c;
  return {a, b, c, gravity.dot(e1), gravity.dot(e2)};
}

// Whether the texel centre (u, v) lies in the triangle with uv corners p0, p1, p2 (edges included).
bool holds(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2, double u, double v) {
  const auto side = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (b.x() - a.x()) * (v - a.y()) - (b.y() - a.y()) * (u - a.x());
  };
  const double s0 = side(p0, p1), s1 = side(p1, p2), s2 = side(p2, p0);
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

// Gives `visit` each texel whose centre the triangle's uvs hold, in row order, until it returns
// false; whether it went through them all. The texels looked at are those of its uv box, (i + ½)/W
// in [least u, greatest u], clamped to the texture before they are counted in ints: a uv far off
// the texture stays a double.
template <class Visit>
bool for_each_texel_held(const TissueMesh& mesh, const TissueMesh::Triangle& t, const TexturePanel& panel,
                         Visit&& visit) {
  const Eigen::Vector2d& p0 = mesh.uvs[t.uv[0]];
  const Eigen::Vector2d& p1 = mesh.uvs[t.uv[1]];
  const Eigen::Vector2d& p2 = mesh.uvs[t.uv[2]];
  const double w = panel.width_px, h = panel.height_px;
  const auto first = [](double low, double n) { return int(std::clamp(std::ceil(low * n - 0.5), 0.0, n)); };
  const auto last = [](double high, double n) { return int(std::clamp(std::floor(high * n - 0.5), -1.0, n - 1)); };
  const int i0 = first(std::min({p0.x(), p1.x(), p2.x()}), w), i1 = last(std::max({p0.x(), p1.x(), p2.x()}), w);
  const int j0 = first(std::min({p0.y(), p1.y(), p2.y()}), h), j1 = last(std::max({p0.y(), p1.y(), p2.y()}), h);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      if (holds(p0, p1, p2, (i + 0.5) / w, (j + 0.5) / h) &&
          !visit(std::size_t(j) * std::size_t(panel.width_px) + std::size_t(i)))
        return false;
  return true;
}

// Off-surface texels take their nearest covered texel's values: a breadth-first sweep from every
// covered texel at once, in row order, so the first to reach a texel gives it its values.
void fill_off_surface(SurfaceMaps& maps) {
  const int w = maps.width, h = maps.height;
  std::vector<bool> filled(std::size_t(w) * h, false);
  std::deque<std::size_t> queue;
  for (std::size_t t = 0; t < filled.size(); ++t)
    if (maps.frame[kSurfaceFrameChannels * t + 3] != 0.0f) {
      filled[t] = true;
      queue.push_back(t);
    }
  while (!queue.empty()) {
    const std::size_t t = queue.front();
    queue.pop_front();
    const int i = int(t % std::size_t(w)), j = int(t / std::size_t(w));
    const int di[] = {0, -1, 1, 0}, dj[] = {-1, 0, 0, 1};
    for (int k = 0; k < 4; ++k) {
      const int ni = i + di[k], nj = j + dj[k];
      if (ni < 0 || nj < 0 || ni >= w || nj >= h) continue;
      const std::size_t n = std::size_t(nj) * w + ni;
      if (filled[n]) continue;
      filled[n] = true;
      for (int c = 0; c < 3; ++c) maps.frame[kSurfaceFrameChannels * n + c] = maps.frame[kSurfaceFrameChannels * t + c];
      for (int c = 0; c < kSurfaceGravityChannels; ++c)
        maps.gravity[kSurfaceGravityChannels * n + c] = maps.gravity[kSurfaceGravityChannels * t + c];
      queue.push_back(n);
    }
  }
}

}  // namespace

SurfaceMaps bake_surface_maps(const TissueMesh& mesh, const TexturePanel& panel, const Eigen::Vector3d& gravity) {
  SurfaceMaps maps;
  maps.width = panel.width_px;
  maps.height = panel.height_px;
  const std::size_t texels = std::size_t(panel.width_px) * std::size_t(panel.height_px);
  maps.frame.assign(texels * kSurfaceFrameChannels, 0.0f);
  maps.gravity.assign(texels * kSurfaceGravityChannels, 0.0f);
  std::vector<bool> taken(texels, false);
  for (const TissueMesh::Triangle& t : mesh.triangles) {
    std::optional<TexelValues> values;
    for_each_texel_held(mesh, t, panel, [&](std::size_t texel) {
      if (taken[texel]) return true;
      if (!values) values = frame_values(panel_to_surface(mesh, t, panel), gravity);
      taken[texel] = true;
      float* f = &maps.frame[kSurfaceFrameChannels * texel];
      f[0] = float(values->a);
      f[1] = float(values->b);
      f[2] = float(values->c);
      f[3] = 1.0f;
      maps.gravity[kSurfaceGravityChannels * texel] = float(values->gx);
      maps.gravity[kSurfaceGravityChannels * texel + 1] = float(values->gy);
      ++maps.covered;
      return true;
    });
  }
  if (maps.covered == 0)
    throw std::invalid_argument("the mesh covers no texel of the " + std::to_string(panel.width_px) + " × " +
                                std::to_string(panel.height_px) + " texture: its uvs hold no texel's centre");
  fill_off_surface(maps);
  return maps;
}

bool covers_a_texel(const TissueMesh& mesh, const TexturePanel& panel) {
  for (const TissueMesh::Triangle& t : mesh.triangles)
    if (!for_each_texel_held(mesh, t, panel, [](std::size_t) { return false; })) return true;
  return false;
}

PanelStretch panel_stretch(const TissueMesh& mesh, const TexturePanel& panel) {
  PanelStretch s{INFINITY, 0.0};
  for (const TissueMesh::Triangle& t : mesh.triangles) {
    // J's singular values are the square roots of JᵀJ's eigenvalues (a symmetric 2 × 2).
    const Eigen::Matrix2d g = [&] {
      const Eigen::Matrix<double, 3, 2> j = panel_to_surface(mesh, t, panel);
      return Eigen::Matrix2d(j.transpose() * j);
    }();
    const double mean = 0.5 * (g(0, 0) + g(1, 1));
    const double spread = std::hypot(0.5 * (g(0, 0) - g(1, 1)), g(0, 1));
    s.least = std::min(s.least, std::sqrt(std::max(mean - spread, 0.0)));
    s.greatest = std::max(s.greatest, std::sqrt(mean + spread));
  }
  return s;
}

}  // namespace bleedsim
