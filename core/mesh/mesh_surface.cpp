#include "core/mesh/mesh_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace bleedsim {
namespace {

constexpr int kLeafTriangles = 4;

}  // namespace

Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};  // corner a
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};  // corner b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {  // edge ab
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};  // corner c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {  // edge ac
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {  // edge bc
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denominator = 1 / (va + vb + vc);  // the face
  const double v = vb * denominator, w = vc * denominator;
  return {1 - v - w, v, w};
}

MeshSurface::MeshSurface(TissueMesh mesh) : mesh_(std::move(mesh)) {
  order_.resize(mesh_.triangles.size());
  for (std::size_t t = 0; t < order_.size(); ++t) order_[t] = int(t);
  if (!order_.empty()) build(0, int(order_.size()));
}

int MeshSurface::build(int first, int count) {
  const auto corner = [&](int t, int k) { return mesh_.positions[mesh_.triangles[t].corner[k]]; };
  const auto centroid = [&](int t) -> Eigen::Vector3d { return (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0; };
  Node node;
  for (int i = first; i < first + count; ++i)
    for (int k = 0; k < 3; ++k) node.box.extend(corner(order_[i], k));
  const int index = int(nodes_.size());
  nodes_.push_back(node);
  if (count <= kLeafTriangles) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  // Split at the median centroid along the box's longest axis (ties by triangle index: the same
  // tree on every machine).
  int axis = 0;
  node.box.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int s, int t) {
                     const double cs = centroid(s)[axis], ct = centroid(t)[axis];
                     return cs < ct || (cs == ct && s < t);
                   });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

SurfacePoint MeshSurface::closest(const Eigen::Vector3d& p) const {
  SurfacePoint best;
  double best_sq = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (node.box.squaredExteriorDistance(p) > best_sq) continue;
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int t = order_[i];
        const auto& c = mesh_.triangles[t].corner;
        const Eigen::Vector3d& a = mesh_.positions[c[0]];
        const Eigen::Vector3d& b = mesh_.positions[c[1]];
        const Eigen::Vector3d& d = mesh_.positions[c[2]];
        const Eigen::Vector3d w = closest_on_triangle(p, a, b, d);
        const Eigen::Vector3d q = w[0] * a + w[1] * b + w[2] * d;
        const double sq = (q - p).squaredNorm();
        if (sq < best_sq || (sq == best_sq && t < best.triangle)) {
          best_sq = sq;
          best = {t, w, q, 0.0};
        }
      }
      continue;
    }
    // The nearer child last, so that it is searched first.
    const double left = nodes_[node.left].box.squaredExteriorDistance(p);
    const double right = nodes_[node.right].box.squaredExteriorDistance(p);
    stack.push_back(left < right ? node.right : node.left);
    stack.push_back(left < right ? node.left : node.right);
  }
  best.distance_mm = std::sqrt(best_sq);
  return best;
}

Eigen::Vector2d MeshSurface::uv(const SurfacePoint& at) const {
  const auto& t = mesh_.triangles[at.triangle].uv;
  return at.barycentric[0] * mesh_.uvs[t[0]] + at.barycentric[1] * mesh_.uvs[t[1]] +
         at.barycentric[2] * mesh_.uvs[t[2]];
}

}  // namespace bleedsim
