#include "core/mesh/polygon_triangles.h"

#include <algorithm>
#include <optional>

#include <Eigen/Geometry>

namespace bleedsim {
namespace {

// |b − a|², summed x, y, z in the order in which tinyobjloader compared a quad's diagonals, so that
// a quad is split as it was, to the last bit, on a tie too.
double squared_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double x = b.x() - a.x(), y = b.y() - a.y(), z = b.z() - a.z();
  return x * x + y * y + z * z;
}

// Twice the signed area of the triangle a, b, c: positive when it turns anticlockwise.
double turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Whether the anticlockwise triangle a, b, c holds p, its edges and corners included.
bool holds(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& p) {
  return turn(a, b, p) >= 0 && turn(b, c, p) >= 0 && turn(c, a, p) >= 0;
}

// The corners in the plane the polygon faces, along axes u, v with u × v its Newell normal, so that
// it turns anticlockwise there (a polygon that is not flat, as most quads of a curved mesh are not,
// is seen along its mean normal); none when it faces no way: it has no area.
std::optional<std::vector<Eigen::Vector2d>> in_its_plane(const std::vector<Eigen::Vector3d>& corners) {
  const Eigen::Vector3d& origin = corners.front();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) normal += (corners[k] - origin).cross(corners[k + 1] - origin);
  if (!(normal.norm() > 0)) return std::nullopt;
  const Eigen::Vector3d w = normal.normalized(), u = w.unitOrthogonal(), v = w.cross(u);
  std::vector<Eigen::Vector2d> flat;
  for (const Eigen::Vector3d& p : corners) flat.emplace_back((p - origin).dot(u), (p - origin).dot(v));
  return flat;
}

// The triangle a, b, c of a polygon's corners (a, b, c in its order, round the end at most once)
// written from its lowest corner, as tinyobjloader wrote a quad's.
std::array<int, 3> from_lowest(int a, int b, int c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

}  // namespace

std::vector<std::array<int, 3>> polygon_triangles(const std::vector<Eigen::Vector3d>& corners) {
  const int n = int(corners.size());
  const std::optional<std::vector<Eigen::Vector2d>> flat = in_its_plane(corners);
  if (!flat) return {};
  const std::vector<Eigen::Vector2d>& p = *flat;
  // The corners not yet cut off, as a ring.
  std::vector<int> before(n), after(n);
  std::vector<bool> left(n, true);
  for (int k = 0; k < n; ++k) before[k] = (k + n - 1) % n, after[k] = (k + 1) % n;
  // An ear: a corner that turns the polygon's way and whose triangle holds no other corner left. In
  // a polygon that does not touch itself, cutting one off changes whether only its two neighbours
  // are ears (a convex corner inside another's triangle would make that polygon touch itself), so
  // only theirs are found again.
  const auto is_ear = [&](int b) {
    const int a = before[b], c = after[b];
    if (!(turn(p[a], p[b], p[c]) > 0)) return false;
    for (int k = after[c]; k != a; k = after[k])
      if (holds(p[a], p[b], p[c], p[k])) return false;
    return true;
  };
  std::vector<bool> ear(n);
  for (int k = 0; k < n; ++k) ear[k] = is_ear(k);

  std::vector<std::array<int, 3>> triangles;
  for (int corners_left = n; corners_left > 3; --corners_left) {
    int cut = -1;
    double shortest = 0;
    for (int k = 0; k < n; ++k) {
      if (!left[k] || !ear[k]) continue;
      const double length = squared_distance(corners[before[k]], corners[after[k]]);
      if (cut < 0 || length < shortest) cut = k, shortest = length;
    }
    if (cut < 0) return {};
    const int a = before[cut], c = after[cut];
    triangles.push_back(from_lowest(a, cut, c));
    left[cut] = false;
    after[a] = c;
    before[c] = a;
    ear[a] = is_ear(a);
    ear[c] = is_ear(c);
  }
  // The last three: turned the polygon's way unless it crosses itself.
  const int first = int(std::find(left.begin(), left.end(), true) - left.begin());
  if (!is_ear(first)) return {};
  triangles.push_back({first, after[first], after[after[first]]});
  return triangles;
}

}  // namespace bleedsim
