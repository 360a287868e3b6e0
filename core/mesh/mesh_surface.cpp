#include "core/mesh/mesh_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace bleedsim {
namespace {

constexpr int kLeafTriangles = 4;
// How far outside a triangle's barycentric range a segment's crossing may fall and still count: a
// crossing on an edge is then found on both of its triangles, never on neither.
constexpr double kCrossingSlack = 1e-12;
// How far past its ends, as a fraction of its length, a segment may meet a triangle and still pass
// through it: a segment that starts or ends on the surface, to rounding, passes through it.
constexpr double kEndSlack = 1e-9;

// Whether the segment a + t·d, t ∈ [0, 1], meets the box (the slab test), the box grown by a hair so
// that a segment through its face or edge is not lost to the division's rounding.
bool segment_meets_box(const Eigen::Vector3d& a, const Eigen::Vector3d& d, const Eigen::AlignedBox3d& box) {
  const double pad = 1e-9 * (1.0 + box.diagonal().norm());
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double lo = box.min()[k] - pad, hi = box.max()[k] + pad;
    if (d[k] == 0.0) {
      if (a[k] < lo || a[k] > hi) return false;
      continue;
    }
    double near = (lo - a[k]) / d[k], far = (hi - a[k]) / d[k];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) return false;
  }
  return true;
}

// Where the segment a + t·d, t ∈ [0, 1], passes through triangle pqr (Möller & Trumbore), if it does.
std::optional<SegmentCrossing> segment_through_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& d,
                                                        const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                                        const Eigen::Vector3d& r) {
  const Eigen::Vector3d e1 = q - p, e2 = r - p;
  const Eigen::Vector3d pvec = d.cross(e2);
  const double det = e1.dot(pvec);
  // Edge-on (the segment parallel to the triangle's plane, to rounding): it does not pass through.
  if (std::fabs(det) <= 1e-14 * e1.norm() * e2.norm() * d.norm()) return std::nullopt;
  const Eigen::Vector3d s = a - p;
  const double u = s.dot(pvec) / det;
  if (u < -kCrossingSlack || u > 1 + kCrossingSlack) return std::nullopt;
  const Eigen::Vector3d qvec = s.cross(e1);
  const double v = d.dot(qvec) / det;
  if (v < -kCrossingSlack || u + v > 1 + kCrossingSlack) return std::nullopt;
  const double t = e2.dot(qvec) / det;
  if (t < -kEndSlack || t > 1 + kEndSlack) return std::nullopt;
  // The weights, within the slack of the range, clamped into it.
  Eigen::Vector3d w(1 - u - v, u, v);
  w = w.cwiseMax(0.0);
  w /= w.sum();
  SegmentCrossing crossing;
  crossing.t = std::clamp(t, 0.0, 1.0);
  crossing.at.barycentric = w;
  crossing.at.point = w[0] * p + w[1] * q + w[2] * r;
  return crossing;
}

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

std::vector<SegmentCrossing> MeshSurface::crossings(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  std::vector<SegmentCrossing> found;
  if (nodes_.empty()) return found;
  const Eigen::Vector3d d = b - a;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (!segment_meets_box(a, d, node.box)) continue;
    if (node.left >= 0) {
      stack.push_back(node.left);
      stack.push_back(node.right);
      continue;
    }
    for (int i = node.first; i < node.first + node.count; ++i) {
      const int t = order_[i];
      const auto& c = mesh_.triangles[t].corner;
      if (auto crossing = segment_through_triangle(a, d, mesh_.positions[c[0]], mesh_.positions[c[1]],
                                                   mesh_.positions[c[2]])) {
        crossing->at.triangle = t;
        found.push_back(*crossing);
      }
    }
  }
  // Nearest a first; of crossings at the same parameter, the lowest triangle first (the traversal's
  // order is the tree's, not the answer's).
  std::sort(found.begin(), found.end(), [](const SegmentCrossing& x, const SegmentCrossing& y) {
    return x.t < y.t || (x.t == y.t && x.at.triangle < y.at.triangle);
  });
  return found;
}

Eigen::Vector2d MeshSurface::uv(const SurfacePoint& at) const {
  const auto& t = mesh_.triangles[at.triangle].uv;
  return at.barycentric[0] * mesh_.uvs[t[0]] + at.barycentric[1] * mesh_.uvs[t[1]] +
         at.barycentric[2] * mesh_.uvs[t[2]];
}

}  // namespace bleedsim
