#pragma once
// What the tests of the stylus' contact with a tissue mesh share: the contact's parameters, a
// scripted path of the tip, the flat panel, a crease with the closed form of its proxy, the bounds
// of a mesh's normal field, and the turbinate's smooth surface.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/haptics/haptics.h"
#include "core/haptics/mesh_contact.h"
#include "core/io/mesh_obj.h"
#include "tests/test_paths.h"

namespace bleedsim::test {

using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;
constexpr double kT = kHapticPeriod_s;
// The contact's parameters: HapticParams' defaults, k = 500 N/m, b = 0.5 N·s/m, 8 N, device 1.5 N·s/m.
const HapticParams kParams{};
const double kK = kParams.stiffness_N_per_m / 1000.0;  // N/mm
const double kB = kParams.damping_Ns_per_m;

// A scripted path of the tip, one point a tick: straight segments, each at no more than its speed.
struct Path {
  std::vector<Vector3d> points;
  explicit Path(const Vector3d& start) : points{start} {}
  Path& to(const Vector3d& target, double speed_mm_s) {
    const Vector3d from = points.back();
    const int ticks = std::max(1, int(std::ceil((target - from).norm() / (speed_mm_s * kT) - 1e-9)));
    for (int i = 1; i <= ticks; ++i) points.push_back(from + (target - from) * (double(i) / ticks));
    return *this;
  }
  Path& hold(int ticks) {
    for (int i = 0; i < ticks; ++i) points.push_back(points.back());
    return *this;
  }
  // The longest step and the largest change of step between ticks, mm.
  double step() const {
    double d = 0;
    for (std::size_t i = 1; i < points.size(); ++i) d = std::max(d, (points[i] - points[i - 1]).norm());
    return d;
  }
  double turn() const {
    double d = 0;
    for (std::size_t i = 2; i < points.size(); ++i)
      d = std::max(d, (points[i] - 2 * points[i - 1] + points[i - 2]).norm());
    return d;
  }
};

inline std::vector<MeshTouch> run(MeshContact& contact, const Path& path) {
  std::vector<MeshTouch> touches;
  for (const Vector3d& p : path.points) touches.push_back(contact.touch(p));
  return touches;
}

inline double largest_force_step(const std::vector<MeshTouch>& touches) {
  double d = 0;
  for (std::size_t i = 1; i < touches.size(); ++i) d = std::max(d, (touches[i].force_N - touches[i - 1].force_N).norm());
  return d;
}

inline TissueMesh moved(TissueMesh mesh, const Vector3d& by) {
  for (Vector3d& p : mesh.positions) p += by;
  return mesh;
}

inline TissueMesh flat_panel() { return load_tissue_mesh(test::source_dir() + "/scenarios/meshes/flat-panel.obj"); }

// A crease: two flat faces, each w = 16 mm from its outer edge to the crease along its slope and
// L = 24 mm along the crease (the y axis), meeting at x = z = 0 and turning the surface by `angle`:
// a roof (the crease a ridge) or a valley. Each face is one quad of two triangles whose diagonals
// mirror each other across the crease, so that every crease vertex has as much area on each side
// and its area-weighted normal is the bisector n_R = (0, 0, 1) exactly; the outer vertices' normals
// are their faces', n_A = (−s, 0, c) and n_B = (s, 0, c) (roof; the valley's x flipped), s, c the sine
// and cosine of angle / 2. uv: u across, v down the y axis, so the outside is +z.
constexpr double kFace = 16.0, kLength = 24.0;
struct Crease {
  double angle;
  bool roof;
  double half() const { return angle / 2; }
  // A's slope direction from its outer edge towards the crease, and B's from the crease outwards.
  Vector3d along_a() const { return {std::cos(half()), 0, roof ? std::sin(half()) : -std::sin(half())}; }
  Vector3d along_b() const { return {std::cos(half()), 0, roof ? -std::sin(half()) : std::sin(half())}; }
  Vector3d normal_a() const { return {roof ? -std::sin(half()) : std::sin(half()), 0, std::cos(half())}; }
  Vector3d normal_b() const { return {roof ? std::sin(half()) : -std::sin(half()), 0, std::cos(half())}; }
  double surface_z(double x) const { return (roof ? -1 : 1) * std::tan(half()) * std::fabs(x); }
  double outer_x() const { return kFace * std::cos(half()); }

  TissueMesh mesh() const {
    TissueMesh m;
    const Vector3d a = -kFace * along_a(), b = kFace * along_b(), y(0, kLength, 0);
    m.positions = {a, a + y, Vector3d::Zero(), y, b, b + y};  // a0 a1 r0 r1 b0 b1
    for (const Vector3d& p : m.positions) m.uvs.emplace_back((p.x() - a.x()) / (b.x() - a.x()), 1.0 - p.y() / kLength);
    const auto tri = [](int i, int j, int k) { return TissueMesh::Triangle{{i, j, k}, {i, j, k}}; };
    m.triangles = {tri(0, 2, 3), tri(0, 3, 1), tri(2, 4, 3), tri(3, 4, 5)};
    return m;
  }

  // The shading normal's largest tilt from its face (at the crease, n_R against n_A: angle / 2) and
  // its largest turn per mm across a face: N(s) = (1 − s/w)·n_A + (s/w)·n_R turns fastest where it is
  // shortest, at s = w/2, |dn/ds| = |n_R − n_A| / (w·|N|) = 2 sin(angle/4) / (w cos(angle/4)).
  double tilt() const { return half(); }
  double turn_per_mm() const { return 2 * std::tan(angle / 4) / kFace; }

  // The closed form of the proxy for a device in the cross-section (x, z): the surface point P(s) whose
  // interpolated normal N(s) passes through it, cross(x − P(s), N(s)) = 0 — a quadratic in s on each
  // face, the root within the face. Returns P, h = (P − x)·n and n = N/|N|.
  struct Proxy2d {
    Vector3d point;
    double depth;
    Vector3d normal;
  };
  Proxy2d proxy(const Vector3d& x) const {
    // Past an outer edge the tissue continues as the face's plane, the proxy on the edge.
    const Vector3d a = -kFace * along_a() + Vector3d(0, x.y(), 0), b = kFace * along_b() + Vector3d(0, x.y(), 0);
    if ((x - a).dot(along_a()) < 0) return {a, (a - x).dot(normal_a()), normal_a()};
    if ((x - b).dot(along_b()) > 0) return {b, (b - x).dot(normal_b()), normal_b()};
    const auto cross = [](const Vector3d& u, const Vector3d& v) { return u.x() * v.z() - u.z() * v.x(); };
    const Vector3d ends[2] = {-kFace * along_a(), Vector3d::Zero()};
    const Vector3d dirs[2] = {along_a(), along_b()};
    const Vector3d n0[2] = {normal_a(), Vector3d(0, 0, 1)}, n1[2] = {Vector3d(0, 0, 1), normal_b()};
    for (int f = 0; f < 2; ++f) {
      const Vector3d d = x - ends[f], m = (n1[f] - n0[f]) / kFace;
      // cross(d − s·t, n0 + s·m) = cross(d, n0) + s·(cross(d, m) − cross(t, n0)) − s²·cross(t, m)
      const double c0 = cross(d, n0[f]), c1 = cross(d, m) - cross(dirs[f], n0[f]), c2 = -cross(dirs[f], m);
      double roots[2];
      int count = 0;
      if (std::fabs(c2) < 1e-15) {
        roots[count++] = -c0 / c1;
      } else {
        const double disc = c1 * c1 - 4 * c2 * c0;
        if (disc < 0) continue;
        const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
        roots[count++] = q / c2;
        roots[count++] = c0 / q;
      }
      for (int i = 0; i < count; ++i) {
        const double s = roots[i];
        if (s < -1e-9 || s > kFace + 1e-9) continue;
        const Vector3d p = ends[f] + s * dirs[f] + Vector3d(0, x.y(), 0);
        const Vector3d n = (n0[f] + s * m).normalized();
        return {p, (p - x).dot(n), n};
      }
    }
    ADD_FAILURE() << "no proxy for " << x.transpose();
    return {x, 0, Vector3d::Zero()};
  }
};

// The largest tilt τ of a mesh's shading normal from its face's normal, and its largest turn κ per mm
// of the surface. On a triangle, N(w) = n0 + w1·m1 + w2·m2 with m_i = n_i − n0, and a step dP in its
// plane changes the weights by E⁺·dP (E = [e1 e2]), so |dN| ≤ σ_max(M·E⁺)·|dP|; n = N/|N| turns by
// |dn| ≤ |dN| / |N|, and |N| ≥ N·n_face ≥ min_i n_i·n_face = cos τ_triangle (the weights sum to 1).
struct NormalField {
  double tilt = 0;         // τ, rad
  double turn_per_mm = 0;  // κ, rad/mm
};
inline NormalField normal_field(const MeshContact& contact, const TissueMesh& mesh, std::vector<int> triangles = {}) {
  if (triangles.empty())
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) triangles.push_back(int(t));
  NormalField field;
  for (const int t : triangles) {
    const auto& c = mesh.triangles[t].corner;
    double tilt = 0;
    for (int k = 0; k < 3; ++k)
      tilt = std::max(tilt, std::acos(std::min(1.0, contact.vertex_normal(c[k]).dot(contact.face_normal(t)))));
    Eigen::Matrix<double, 3, 2> e, m;
    e << mesh.positions[c[1]] - mesh.positions[c[0]], mesh.positions[c[2]] - mesh.positions[c[0]];
    m << contact.vertex_normal(c[1]) - contact.vertex_normal(c[0]), contact.vertex_normal(c[2]) - contact.vertex_normal(c[0]);
    const Eigen::Matrix<double, 2, 3> e_plus = (e.transpose() * e).inverse() * e.transpose();
    const double sigma = Eigen::JacobiSVD<Eigen::Matrix3d>(m * e_plus).singularValues()[0];
    field.tilt = std::max(field.tilt, tilt);
    field.turn_per_mm = std::max(field.turn_per_mm, sigma / std::cos(tilt));
  }
  return field;
}

// The turbinate's smooth surface, as scripts/make-turbinate writes it (its vertices lie on it), and
// its outward normal ∂S/∂v × ∂S/∂u.
inline Vector3d turbinate_point(double u, double v) {
  const double radius = (4.0 + 3.0 * std::sin(kPi * u)) * (1.0 - 0.4 * v);
  const double angle = (90.0 - 220.0 * v) * kPi / 180.0;
  return {40.0 * u, -6.0 * u * u + radius * std::sin(angle), 2.0 * std::sin(kPi * u) + radius * std::cos(angle)};
}
inline Vector3d turbinate_normal(double u, double v) {
  const double d = 1e-6;
  const Vector3d du = turbinate_point(u + d, v) - turbinate_point(u - d, v);
  const Vector3d dv = turbinate_point(u, v + d) - turbinate_point(u, v - d);
  return dv.cross(du).normalized();
}

}  // namespace bleedsim::test
