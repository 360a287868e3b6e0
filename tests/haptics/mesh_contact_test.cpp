// The stylus' contact with a tissue mesh (core/haptics/mesh_contact.h): the flat mesh against the
// plane of the haptic loop, force continuity past the mesh's boundary and across creases, no
// tunnelling through the curled turbinate, the energy of closed loops, and contact that begins only
// by passing through the surface from outside. Every bound is derived in the comment above its test
// from the spring, the damper, the sweep's step and the normal field's turn; the reference values
// come from closed forms written here, not from the code under test.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <sstream>
#include <vector>

#include "core/haptics/haptics.h"
#include "core/haptics/mesh_contact.h"
#include "core/io/mesh_obj.h"
#include "tests/runtime/scenes_in_code.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

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

std::vector<MeshTouch> run(MeshContact& contact, const Path& path) {
  std::vector<MeshTouch> touches;
  for (const Vector3d& p : path.points) touches.push_back(contact.touch(p));
  return touches;
}

double largest_force_step(const std::vector<MeshTouch>& touches) {
  double d = 0;
  for (std::size_t i = 1; i < touches.size(); ++i) d = std::max(d, (touches[i].force_N - touches[i - 1].force_N).norm());
  return d;
}

TissueMesh moved(TissueMesh mesh, const Vector3d& by) {
  for (Vector3d& p : mesh.positions) p += by;
  return mesh;
}

TissueMesh flat_panel() { return load_tissue_mesh(test::source_dir() + "/scenarios/meshes/flat-panel.obj"); }

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
NormalField normal_field(const MeshContact& contact, const TissueMesh& mesh, std::vector<int> triangles = {}) {
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
Vector3d turbinate_point(double u, double v) {
  const double radius = (4.0 + 3.0 * std::sin(kPi * u)) * (1.0 - 0.4 * v);
  const double angle = (90.0 - 220.0 * v) * kPi / 180.0;
  return {40.0 * u, -6.0 * u * u + radius * std::sin(angle), 2.0 * std::sin(kPi * u) + radius * std::cos(angle)};
}
Vector3d turbinate_normal(double u, double v) {
  const double d = 1e-6;
  const Vector3d du = turbinate_point(u + d, v) - turbinate_point(u - d, v);
  const Vector3d dv = turbinate_point(u, v + d) - turbinate_point(u, v - d);
  return dv.cross(du).normalized();
}

// Test 1. Where the flat mesh and the flat panel agree — the tip over the panel's interior, pressed
// straight in — the force is the plane's of HapticLoop, with the same parameters: a spring on the
// depth, a damper on the speed along +z, clamped to [0, 8 N]. The flat panel's vertex normals are
// +z exactly, so the proxy is the tip's foot and its depth is the plane's; only rounding differs
// (mm here, m there): 1e-12 N is some 500 ulps of the 8 N cap.
TEST(MeshContact, TheFlatMeshIsThePlaneOverThePanel) {
  Scene scene = test::scene_in_code(true);
  scene.domain = Domain{64, 48, 32.0, 24.0};  // flat-panel.obj's 32 × 24 mm
  HapticParams h = kParams;
  h.origin_x_mm = 16.0;
  h.origin_y_mm = 12.0;
  scene.haptics = h;
  HapticLoop plane(scene);
  // The mesh in the device frame: panel (X, Y) is device (X − 16, 12 − Y), the OBJ's y being −Y.
  const MeshSurface surface(moved(flat_panel(), Vector3d(-16.0, 12.0, h.surface_z_mm)));
  MeshContact mesh(surface, h);

  Path path(Vector3d(-3, 2, 125));
  path.to({-3, 2, 118}, 10)          // a slow press, 2 mm in
      .hold(5)                       // the spring alone
      .to({-3, 2, 110}, 200)         // a fast press: the damper adds
      .to({5, -4, 111}, 50)          // across the panel at depth, rising a little
      .to({5, -4, 100}, 300)         // past the 8 N cap (20 mm: k·p = 10 N)
      .to({5, -4, 119.9}, 10000)     // pulled out at 10 m/s: the damper outweighs the spring: 0 N
      .to({5, -4, 125}, 100)         // out
      .to({-10, 8, 119}, 100)        // in again near a corner, through the surface
      .to({-10, 8, 126}, 20);
  int in_contact = 0;
  double largest = 0;
  for (std::size_t n = 0; n < path.points.size(); ++n) {
    const Vector3d& p = path.points[n];
    const HapticTick expected = plane.tick(DeviceSample{p / 1000.0, 0}).record;
    const MeshTouch got = mesh.touch(p);
    ASSERT_EQ(got.contact, expected.contact) << "tick " << n;
    ASSERT_NEAR(got.penetration_mm, 1000.0 * expected.penetration_m, 1e-9) << "tick " << n;
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(got.force_N[k], expected.force_N[k], 1e-12) << "tick " << n;
    largest = std::max(largest, (got.force_N - expected.force_N).cwiseAbs().maxCoeff());
    in_contact += got.contact;
  }
  std::cout << "flat mesh against the plane: " << in_contact << " ticks in contact, largest force difference "
            << largest << " N\n";
  EXPECT_GT(in_contact, 300);
}

// Test 2. Past the mesh's boundary. The tip presses 6 mm into the flat panel (3 N at k = 500 N/m),
// sweeps at v = 100 mm/s past its right edge by 8 mm and back, past its top-right corner and back,
// then rises out beyond the edge. On the flat panel every normal is +z (no tilt, no turn), so the
// force's change in a tick is the spring's on the depth's change and the damper's on the normal
// speed's: |ΔF| ≤ k·|Δh| + b·|Δv_n| ≤ k·δ + b·|Δ²x| / T, δ the step (|Δh| ≤ |Δz| ≤ δ) and |Δ²x| the
// change of step (≤ 2δ, a reversal). That also bounds the first tick of contact (k·h + b·v_n with
// h ≤ δ, v_n ≤ δ/T) and the last (a tip within δ of the surface). At δ = 0.1 mm: 0.05 + 0.1 N.
// The plane of HapticLoop, which ends at the panel's edge, drops 3 N → 0 N there in one tick.
TEST(MeshContact, SweepingPastTheBoundaryAtDepthKeepsTheForce) {
  const MeshSurface surface(flat_panel());  // z = 0, x ∈ [0, 32], y ∈ [−24, 0], outside +z
  MeshContact contact(surface, kParams);
  const double v = 100.0, depth = 6.0;
  Path path(Vector3d(26, -12, 2));
  path.to({26, -12, -depth}, v);
  const std::size_t swept_from = path.points.size();
  path.to({40, -12, -depth}, v).to({26, -12, -depth}, v).to({38, 6, -depth}, v);
  const std::size_t at_corner = path.points.size() - 1;
  path.to({26, -12, -depth}, v).to({40, -12, -depth}, v);
  const std::size_t swept_to = path.points.size();
  path.to({40, -12, 2}, v);
  const std::vector<MeshTouch> touches = run(contact, path);

  // At depth the force is the spring's 3 N along +z on every tick, over the panel and past it.
  for (std::size_t n = swept_from; n < swept_to; ++n) {
    ASSERT_TRUE(touches[n].contact) << "tick " << n;
    ASSERT_NEAR(touches[n].force_N.z(), kK * depth, 1e-12) << "tick " << n;
    ASSERT_EQ(touches[n].force_N.x(), 0.0);
    ASSERT_EQ(touches[n].force_N.y(), 0.0);
  }
  // Past the edge the proxy is on the boundary, the tip's distance past it measured in the plane.
  const MeshTouch& beyond = touches[swept_to - 1];
  EXPECT_NEAR(beyond.proxy.point.x(), 32.0, 1e-12);
  EXPECT_NEAR(beyond.proxy.point.y(), -12.0, 1e-12);
  EXPECT_NEAR(beyond.beyond_edge_mm, 8.0, 1e-12);
  EXPECT_NEAR(surface.uv(beyond.proxy).x(), 1.0, 1e-12);
  // Past the corner, beyond both edges, the proxy stays on the corner.
  EXPECT_NEAR((touches[at_corner].proxy.point - Vector3d(32, 0, 0)).norm(), 0.0, 1e-12);
  // Rising out beyond the edge the force falls with the depth, k·h − b·v_n, to none above z = 0.
  for (std::size_t n = swept_to; n < touches.size(); ++n) {
    const double h = -path.points[n].z();
    EXPECT_EQ(touches[n].contact, h > 0) << "tick " << n;
    if (h > 0) {
      EXPECT_NEAR(touches[n].force_N.z(), std::max(0.0, kK * h - kB * v / 1000.0), 1e-12) << "tick " << n;
    }
  }
  EXPECT_FALSE(touches.back().contact);

  const double bound = kK * path.step() + kB * (path.turn() / 1000.0) / kT;
  const double largest = largest_force_step(touches);
  std::cout << "boundary sweep at " << v << " mm/s, 6 mm deep: largest |ΔF| in a tick " << largest
            << " N, bound k·δ + b·|Δ²x|/T = " << bound << " N\n";
  EXPECT_LE(largest, bound);
}

// Test 3. Across a crease. For a roof and a valley turning by 30°, 60° and 90°, the tip presses in
// over face A and sweeps straight along x at a fixed height under the crease to face B and back, at
// v = 50 mm/s. The proxy is the closed form's (Crease::proxy, to 1e-9 mm), and the force's change
// in a tick is bounded by the spring, the damper and the normal field. Along the segment between two
// ticks the proxy P, depth h and normal n move continuously with the tip x, and x = P − h·n gives
//   dx = dP − dh·n − h·dn, so |dx| ≥ |dx ⊥ n| ≥ (cos τ − h·κ)·|dP|      (dP in a face tilted ≤ τ
//                                                                      from n; |dn| ≤ κ·|dP|)
//   dh = −n·dx + n·dP, so |dh| ≤ |dx| + sin τ·|dP|
// with τ the largest tilt of the shading normal from its face and κ its largest turn per mm. A tick's
// step δ then moves the proxy by at most L = δ / (cos τ − h_max·κ), turns the normal by at most κ·L,
// changes the depth by at most δ + sin τ·L and the normal speed v_n = n·Δx/T by at most
// (|Δ²x| + κ·L·δ) / T; the force f·n, f = clamp(k·h − b·v_n, 0, f_max), changes by at most
//   |ΔF| ≤ k·(δ + sin τ·L) + b·(|Δ²x| + κ·L·δ)/T + f_max·κ·L,
// f_max = min(8 N, k·h_max + b·δ/T), h_max the closed form's deepest point of the path, |Δ²x| the
// path's largest change of step (2δ where it turns back, which also covers the first tick of
// contact: k·h + b·v_n with h ≤ δ + sin τ·L and v_n ≤ δ/T).
TEST(MeshContact, SweepingAcrossACreaseTurnsTheForceContinuously) {
  for (const double degrees : {30.0, 60.0, 90.0})
    for (const bool roof : {true, false}) {
      const Crease crease{degrees * kPi / 180.0, roof};
      const MeshSurface surface(crease.mesh());
      MeshContact contact(surface, kParams);
      // The crease's normals are the closed form's.
      ASSERT_NEAR((contact.vertex_normal(2) - Vector3d(0, 0, 1)).norm(), 0.0, 1e-15);
      ASSERT_NEAR((contact.vertex_normal(0) - crease.normal_a()).norm(), 0.0, 1e-15);
      ASSERT_NEAR((contact.vertex_normal(5) - crease.normal_b()).norm(), 0.0, 1e-15);

      // Under the crease at a height 3 mm below the faces' lowest point over x ∈ [−6, 6] mm.
      const double reach = 6.0, v = 50.0, y = kLength / 2;
      const double z = roof ? crease.surface_z(reach) - 3.0 : -3.0;
      Path path(Vector3d(-reach, y, crease.surface_z(-reach) + 2.0));
      path.to({-reach, y, z}, v);
      const std::size_t swept_from = path.points.size();
      path.to({reach, y, z}, v).to({-reach, y, z}, v);
      const std::vector<MeshTouch> touches = run(contact, path);

      double h_max = 0;
      for (int i = 0; i <= 4000; ++i) h_max = std::max(h_max, crease.proxy({-reach + 2 * reach * i / 4000.0, y, z}).depth);
      const double delta = path.step(), tau = crease.tilt(), kappa = crease.turn_per_mm();
      ASSERT_GT(std::cos(tau) - h_max * kappa, 0.0);
      const double reach_P = delta / (std::cos(tau) - h_max * kappa);
      const double f_max = std::min(kParams.max_force_N, kK * h_max + kB * (delta / 1000.0) / kT);
      const double bound = kK * (delta + std::sin(tau) * reach_P) +
                           kB * ((path.turn() + kappa * reach_P * delta) / 1000.0) / kT + f_max * kappa * reach_P;

      const double largest = largest_force_step(touches);
      double largest_turn = 0;
      for (std::size_t n = swept_from; n < touches.size(); ++n) {
        ASSERT_TRUE(touches[n].contact) << degrees << "° tick " << n;
        const Crease::Proxy2d expected = crease.proxy(path.points[n]);
        ASSERT_NEAR((touches[n].proxy.point - expected.point).norm(), 0.0, 1e-9) << degrees << "° tick " << n;
        ASSERT_NEAR(touches[n].penetration_mm, expected.depth, 1e-9) << degrees << "° tick " << n;
        largest_turn = std::max(largest_turn, std::acos(std::min(1.0, touches[n].normal.dot(touches[n - 1].normal))));
      }
      // The normal turns one way on the way over (its x grows on a roof, falls in a valley) and back.
      const std::size_t turn_back = swept_from + (touches.size() - swept_from) / 2;
      for (std::size_t n = swept_from + 1; n < turn_back; ++n)
        ASSERT_GE((roof ? 1 : -1) * (touches[n].normal.x() - touches[n - 1].normal.x()), -1e-15) << "tick " << n;
      std::cout << (roof ? "roof " : "valley ") << degrees << "°, h_max " << h_max << " mm: largest |ΔF| "
                << largest << " N (bound " << bound << " N), largest turn of the normal " << largest_turn
                << " rad (bound κ·L = " << kappa * reach_P << ")\n";
      EXPECT_LE(largest, bound);
      EXPECT_LE(largest_turn, kappa * reach_P);
    }
}


// Test 4. The curled turbinate is a sheet: behind its outside lies the inside of the curl and, across
// it, the sheet again. A contact without memory (the surface's nearest point) would take the far
// wall once the tip is nearer to it, and push the tip on through. The proxy instead moves only as the
// walk carries it: by test 3's argument, a tick's step δ moves it at most L = δ / (cos τ − H·κ), with
// τ and κ the normal field's largest tilt and turn (over the whole mesh, or over the triangles the
// proxy stays on) and H the deepest the tip is along the step. H is the last tick's depth plus 0.1 mm,
// which holds while δ·(1 + sin τ / (cos τ − H·κ)) ≤ 0.1 mm (|dh| ≤ |dx| + sin τ·|dP|), checked too.
// (a) Sweeps 1.5 mm under the outside along the curl and round it, at 50 mm/s: contact throughout,
//     every tick's proxy step within L.
// (b) A press straight in at the top near the tail (u = 0.9, v = 0.1, curl radius R = 4.73 mm) to
//     0.9·R, at 20 mm/s, past where the nearest point of the surface flips to the far wall: the proxy
//     stays within 1 mm of where the tip entered (on the triangles within 1.5 mm of it, whose τ and κ
//     give L), the force still pushes out there, while the nearest point ends more than 5 mm away.
TEST(MeshContact, TheProxyNeverTunnelsThroughTheCurledTurbinate) {
  const MeshSurface surface(load_tissue_mesh(test::source_dir() + "/scenarios/meshes/turbinate.obj"));
  const TissueMesh& mesh = surface.mesh();
  MeshContact contact(surface, kParams);
  const auto steps_within = [](const std::vector<MeshTouch>& touches, const Path& path, const NormalField& field,
                               std::size_t from) {
    double worst = 0;  // the largest step as a fraction of its bound
    for (std::size_t n = from + 1; n < touches.size(); ++n) {
      const double delta = (path.points[n] - path.points[n - 1]).norm();
      const double h = touches[n - 1].penetration_mm + 0.1;
      const double margin = std::cos(field.tilt) - h * field.turn_per_mm;
      EXPECT_GT(margin, 0.0) << "tick " << n;
      EXPECT_LE(delta * (1 + std::sin(field.tilt) / margin), 0.1) << "tick " << n;
      const double step = (touches[n].proxy.point - touches[n - 1].proxy.point).norm();
      EXPECT_LE(step, delta / margin) << "tick " << n;
      worst = std::max(worst, step / (delta / margin));
    }
    return worst;
  };

  // (a) The sweeps.
  const NormalField field = normal_field(contact, mesh);
  const double depth = 1.5;
  const auto under = [&](double u, double v) { return Vector3d(turbinate_point(u, v) - depth * turbinate_normal(u, v)); };
  Path path(turbinate_point(0.5, 0.41) + 3.0 * turbinate_normal(0.5, 0.41));
  path.to(under(0.5, 0.41), 50);
  const auto sweep = [&](double u0, double v0, double u1, double v1, double bulge) {
    for (int i = 1; i <= 200; ++i) {
      const double s = i / 200.0;
      path.to(under(u0 + (u1 - u0) * s, v0 + (v1 - v0) * s - bulge * std::sin(kPi * s)), 50);
    }
  };
  sweep(0.5, 0.41, 0.15, 0.41, 0);     // along the front towards the head
  sweep(0.15, 0.41, 0.85, 0.41, 0.3);  // to the tail, over the top and back down
  sweep(0.85, 0.41, 0.85, 0.91, 0);    // round under the curl towards its lip
  sweep(0.85, 0.91, 0.5, 0.41, 0);     // back
  const std::vector<MeshTouch> touches = run(contact, path);
  std::size_t first = 0;
  while (first < touches.size() && !touches[first].contact) ++first;
  ASSERT_LT(first, touches.size());
  for (std::size_t n = first; n < touches.size(); ++n) ASSERT_TRUE(touches[n].contact) << "tick " << n;
  const double worst_sweep = steps_within(touches, path, field, first);

  // (b) The press through the curl's axis. The triangles within 1.5 mm of the entry and their field.
  const double u = 0.9, v = 0.1, radius = (4.0 + 3.0 * std::sin(kPi * u)) * (1 - 0.4 * v);
  const Vector3d entry = turbinate_point(u, v), out = turbinate_normal(u, v);
  std::vector<int> near;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& c = mesh.triangles[t].corner;
    const Vector3d w = closest_on_triangle(entry, mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]);
    const Vector3d q = w[0] * mesh.positions[c[0]] + w[1] * mesh.positions[c[1]] + w[2] * mesh.positions[c[2]];
    if ((q - entry).norm() <= 1.5) near.push_back(int(t));
  }
  const NormalField local = normal_field(contact, mesh, near);
  MeshContact press(surface, kParams);
  Path down(entry + 2.0 * out);
  down.to(entry - 0.9 * radius * out, 20);
  const std::vector<MeshTouch> pressed = run(press, down);
  std::size_t began = 0;
  while (began < pressed.size() && !pressed[began].contact) ++began;
  ASSERT_LT(began, pressed.size());
  double farthest = 0;
  for (std::size_t n = began; n < pressed.size(); ++n) {
    ASSERT_TRUE(pressed[n].contact) << "tick " << n;
    farthest = std::max(farthest, (pressed[n].proxy.point - entry).norm());
  }
  EXPECT_LE(farthest, 1.0);
  const double worst_press = steps_within(pressed, down, local, began);
  const double nearest_away = (surface.closest(down.points.back()).point - entry).norm();
  EXPECT_GT(nearest_away, 5.0);
  EXPECT_GT(pressed.back().force_N.dot(out), 0.0);
  std::cout << "turbinate: sweeps 1.5 mm deep (τ " << field.tilt << " rad, κ " << field.turn_per_mm
            << " /mm): largest proxy step " << worst_sweep << " of its bound; press to " << pressed.back().penetration_mm
            << " mm (local τ " << local.tilt << ", κ " << local.turn_per_mm << "): proxy within " << farthest
            << " mm of the entry, largest step " << worst_press << " of its bound, while the nearest point of the "
            << "surface is " << nearest_away << " mm away\n";
}

// Test 5. Passivity. The energy the virtual tissue returns to the device up to tick n is
// W(n) = Σ_{k<n} F_k·(x_{k+1} − x_k): the force held through each tick (zero-order hold) times the
// tip's step. The device's own damping B dissipates D(n) = Σ_{k<n} B·|x_{k+1} − x_k|² / T (its speed
// Δx/T held over T). The coupled system — hand, device, virtual tissue — gains no energy when
// W(n) ≤ D(n). For a sampled spring and damper along a fixed plane Colgate & Schenkel's condition
// B > k·T/2 + |b| secures it: holding the spring's force through a tick returns at most ½·k·|Δx|² more
// than the continuous spring would, the one-tick-late damper at most b·|Δx|²/T. Force shading's field
// is not conservative: along the shading normal, k·h·n·dx = −d(½k·h²) + k·h·n·dP, so a loop returns
// W_field = ∮ k·h·n·dP, up to k·h_max·sin τ·(the proxy's path) whatever its speed; unbounded, a loop
// from A's middle to a 90° roof's crease and out there returned 7.1 mJ at 3 mm against D = 0.59 mJ.
// The energy bound (mesh_contact.h) limits |F_n| to √(4B·R_n/T), R_n = D − W over the contact so far:
// whatever the next step Δx, B·|Δx|²/T − F_n·Δx ≥ −T·|F_n|²/(4B), so R never falls below 0.
//
// Checked here, with W, D and R kept by the test from the path and the forces alone:
// (a) W(n) ≤ D(n) at every tick of every loop, and T·|F_n|²/(4B) ≤ R_n (both to 1e-12 J, rounding);
// (b) on the flat panel, across its edge and corner, the field is conservative and the bound never
//     binds: the force is the plane's, and W ≤ (k·T/2 + b)·Σ|Δx|²/T, Colgate & Schenkel's excess;
// (c) over a crease the field's own work W_field (from the closed-form proxy, Crease::proxy) is
//     within k·h_max·sin τ·(the proxy's path); where the bound did not bind, force shading's W exceeds
//     W_field by no more than the hold's excess, (k·T·λ/2 + b)·Σ|Δx|²/T (on the mesh the depth and
//     normal vary across a step: with |∇h| ≤ 1 + sin τ/c and |∂n/∂x| ≤ κ/c, c = cos τ − h_max·κ as in
//     test 3, the excess is at most ½·k·λ·|Δx|² a tick, λ = 1 + (sin τ + h_max·κ)/c); where it did,
//     what it took off is reported. Crossing a whole crease symmetrically W_field ≈ 0, but on a roof
//     the field returns energy before the crease and takes it back after, and a slow crossing
//     has dissipated too little to lend: the bound takes most of the force off there.
// The loops: press in, sweep, lift out, back through the air, at 10, 50 and 200 mm/s.
struct Passivity {
  double worst_excess_J = -1e300;  // max over n of W(n) − D(n)
  double worst_bound_excess_J = -1e300;  // max over contact ticks of T·|F_n|²/(4B) − R_n
  double returned_J = 0;           // W over the whole path
  double steps_m2 = 0;             // Σ|Δx|², m²
  int bound_ticks = 0;             // ticks where force shading's force was cut back
  double most_taken_N = 0;         // the largest cut
};
Passivity passivity(const std::vector<MeshTouch>& touches, const Path& path) {
  const double B = kParams.device_damping_Ns_per_m;
  Passivity p;
  double dissipated_J = 0, reserve_J = 0;
  for (std::size_t n = 0; n < touches.size(); ++n) {
    if (n > 0) {
      const Vector3d dx = (path.points[n] - path.points[n - 1]) / 1000.0;
      const double work = touches[n - 1].force_N.dot(dx), loss = B * dx.squaredNorm() / kT;
      p.returned_J += work;
      dissipated_J += loss;
      p.steps_m2 += dx.squaredNorm();
      p.worst_excess_J = std::max(p.worst_excess_J, p.returned_J - dissipated_J);
      reserve_J = touches[n].contact ? reserve_J + loss - work : 0.0;
    }
    if (!touches[n].contact) continue;
    const double force = touches[n].force_N.norm();
    p.worst_bound_excess_J = std::max(p.worst_bound_excess_J, kT * force * force / (4 * B) - reserve_J);
    // Force shading's own force: the spring and damper along n, clamped to [0, 8 N].
    const double v_n = n > 0 ? touches[n].normal.dot(path.points[n] - path.points[n - 1]) / 1000.0 / kT : 0.0;
    const double shaded = std::clamp(kParams.stiffness_N_per_m * touches[n].penetration_mm / 1000.0 - kB * v_n, 0.0,
                                     kParams.max_force_N);
    if (shaded - force > 1e-12) {
      ++p.bound_ticks;
      p.most_taken_N = std::max(p.most_taken_N, shaded - force);
    }
  }
  return p;
}
void expect_passive(const Passivity& p, const std::string& what) {
  EXPECT_LE(p.worst_excess_J, 1e-12) << what;
  EXPECT_LE(p.worst_bound_excess_J, 1e-12) << what;
}

TEST(MeshContact, NoLoopReturnsMoreThanTheDeviceDissipates) {
  const double B = kParams.device_damping_Ns_per_m;
  // The flat panel: in at (24, −12), past the right edge and round the top-right corner, out, back.
  {
    const MeshSurface surface(flat_panel());
    for (const double v : {10.0, 50.0, 200.0}) {
      MeshContact contact(surface, kParams);
      Path path(Vector3d(24, -12, 3));
      path.to({24, -12, -3}, v).to({38, -12, -3}, v).to({38, 6, -3}, v).to({38, 6, 5}, v).to({24, -12, 3}, v);
      const Passivity p = passivity(run(contact, path), path);
      const double demand = passivity_demand_Ns_per_m(kParams) * p.steps_m2 / kT;
      std::cout << "flat panel loop at " << v << " mm/s: W " << p.returned_J * 1e3 << " mJ, (kT/2 + b)·Σ|Δx|²/T "
                << demand * 1e3 << " mJ, D " << B * p.steps_m2 / kT * 1e3 << " mJ, the bound bound on "
                << p.bound_ticks << " ticks\n";
      expect_passive(p, "flat panel");
      EXPECT_EQ(p.bound_ticks, 0);
      EXPECT_LE(p.returned_J, demand);
    }
  }
  for (const double degrees : {30.0, 60.0, 90.0})
    for (const bool roof : {true, false}) {
      const Crease crease{degrees * kPi / 180.0, roof};
      const MeshSurface surface(crease.mesh());
      const double y = kLength / 2, gap = 3.0, outer = crease.outer_x();
      const auto under = [&](double x) { return Vector3d(x, y, crease.surface_z(x) - gap); };
      const auto above = [&](double x) { return Vector3d(x, y, crease.surface_z(x) + gap); };
      const Vector3d past_b = under(outer) + 4.0 * crease.along_b(), past_a = under(-outer) - 4.0 * crease.along_a();
      const double in_a = -outer + 0.25 * std::cos(crease.half());  // 0.25 mm inside A's edge
      const char* names[3] = {"edge to edge", "to the crease", "back past A's edge"};
      // Back through the air: up to 3 mm over the strip's highest point, across, down to the start.
      const double air = (roof ? 0.0 : kFace * std::sin(crease.half())) + gap;
      for (int loop = 0; loop < 3; ++loop) {
        const double start = loop == 0 ? in_a : loop == 1 ? -8.0 : -2.0;
        std::ostringstream line;
        line << (roof ? "roof " : "valley ") << degrees << "°, " << names[loop] << ":";
        for (const double v : {10.0, 50.0, 200.0}) {
          MeshContact contact(surface, kParams);
          Path path(above(start));
          path.to(under(start), v);
          if (loop == 0) path.to(under(0), v).to(past_b, v).to(Vector3d(past_b.x(), y, air), v);
          if (loop == 1) path.to(under(0), v).to(Vector3d(0, y, air), v);
          if (loop == 2) path.to(under(-outer), v).to(past_a, v).to(Vector3d(past_a.x(), y, air), v);
          path.to(Vector3d(start, y, air), v).to(above(start), v);
          const std::vector<MeshTouch> touches = run(contact, path);
          const Passivity p = passivity(touches, path);
          expect_passive(p, line.str() + " at " + std::to_string(v) + " mm/s");

          // The continuous field's work, its deepest point and its proxy's path, from the closed form:
          // the midpoint rule over 20 parts of every step the tip is in contact for some of.
          double field_J = 0, h_max = 0, proxy_path_mm = 0;
          for (std::size_t n = 0; n + 1 < touches.size(); ++n) {
            if (!touches[n].contact && !touches[n + 1].contact) continue;
            const Vector3d dx = path.points[n + 1] - path.points[n];
            Vector3d last = crease.proxy(path.points[n]).point;
            for (int i = 0; i < 20; ++i) {
              const Crease::Proxy2d q = crease.proxy(path.points[n] + dx * ((i + 0.5) / 20));
              if (q.depth <= 0) continue;
              field_J += kK * q.depth * q.normal.dot(dx) / 20 / 1000.0;
              h_max = std::max(h_max, q.depth);
              proxy_path_mm += (q.point - last).norm();
              last = q.point;
            }
          }
          EXPECT_LE(std::fabs(field_J), kK * h_max * std::sin(crease.tilt()) * proxy_path_mm / 1000.0);
          const double dissipated = B * p.steps_m2 / kT;
          if (v == 10.0) line << " W_field " << field_J * 1e3 << " mJ (h_max " << h_max << " mm);";
          line << " at " << v << " mm/s W " << p.returned_J * 1e3 << ", D " << dissipated * 1e3 << " mJ, bound on "
               << p.bound_ticks << " ticks, up to " << p.most_taken_N << " N;";
          if (p.bound_ticks == 0) {
            const double tau = crease.tilt(), kappa = crease.turn_per_mm(), c = std::cos(tau) - h_max * kappa;
            ASSERT_GT(c, 0.0);
            const double lambda = 1 + (std::sin(tau) + h_max * kappa) / c;
            const double coefficient = kParams.stiffness_N_per_m * kT * lambda / 2 + kB;
            EXPECT_LT(coefficient, B);
            EXPECT_LE(p.returned_J - field_J, coefficient * p.steps_m2 / kT) << line.str();
          }
        }
        std::cout << line.str() << "\n";
      }
    }
}

// Test 5b. Whatever the hand does. A restless hand — a random walk whose step changes by up to
// 0.01 mm a tick, so that it reverses, wanders in and out and moves up to 0.1 mm a tick — pressed
// into a 90° roof and valley's crease and the turbinate's front for 20 s each: W(n) ≤ D(n) at every
// tick, the bound of test 5 (a) with no assumption about the path.
TEST(MeshContact, ARestlessHandExtractsNoEnergy) {
  std::vector<std::pair<std::string, TissueMesh>> meshes;
  meshes.emplace_back("roof 90°", Crease{kPi / 2, true}.mesh());
  meshes.emplace_back("valley 90°", Crease{kPi / 2, false}.mesh());
  meshes.emplace_back("turbinate", load_tissue_mesh(test::source_dir() + "/scenarios/meshes/turbinate.obj"));
  const std::vector<Vector3d> centres{{0, kLength / 2, -1.5}, {0, kLength / 2, -1.5},
                                      turbinate_point(0.5, 0.41) - 1.5 * turbinate_normal(0.5, 0.41)};
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const MeshSurface surface(meshes[m].second);
    MeshContact contact(surface, kParams);
    std::mt19937_64 random(17 + m);
    std::uniform_real_distribution<double> jolt(-0.01 / std::sqrt(3.0), 0.01 / std::sqrt(3.0));
    const Vector3d start = centres[m] + Vector3d(0, 0, 4);
    Path path(start);
    path.to(centres[m], 50);
    Vector3d step = Vector3d::Zero();
    while (path.points.size() < 20000) {
      step += Vector3d(jolt(random), jolt(random), jolt(random));
      // Held within 0.1 mm a tick and pulled back towards the centre, so it stays near the surface.
      step = (step - 0.0005 * (path.points.back() - centres[m])).eval();
      if (step.norm() > 0.1) step *= 0.1 / step.norm();
      path.points.push_back(path.points.back() + step);
    }
    const std::vector<MeshTouch> touches = run(contact, path);
    const Passivity p = passivity(touches, path);
    int in_contact = 0;
    for (const MeshTouch& t : touches) in_contact += t.contact;
    std::cout << meshes[m].first << ": " << in_contact << " of " << touches.size() << " ticks in contact, max W − D "
              << p.worst_excess_J * 1e3 << " mJ, W " << p.returned_J * 1e3 << " mJ, D "
              << kParams.device_damping_Ns_per_m * p.steps_m2 / kT * 1e3 << " mJ; bound on " << p.bound_ticks
              << " ticks, up to " << p.most_taken_N << " N\n";
    // Not a physics bound: only that the walk spent a good part of its time in contact, so that the
    // passivity checked below was put to the test (measured 9,603 to 17,751 of 20,000).
    EXPECT_GT(in_contact, 2000) << meshes[m].first;
    expect_passive(p, meshes[m].first);
  }
}

// Test 6. Contact begins only by passing through the surface from its outside. On the flat panel: a
// tip that starts behind it and rises towards it touches nothing, nor as it passes out through it
// from behind, nor one that comes in under the panel from past its edge; a tip that passes in from
// the front touches at once. On the turbinate: a tip that enters the curl through its open back and
// meets the sheet from the inside touches nothing; from the outside it does.
int crossings(const MeshSurface& surface, const Path& path) {
  int count = 0;
  for (std::size_t n = 1; n < path.points.size(); ++n)
    count += int(surface.crossings(path.points[n - 1], path.points[n]).size());
  return count;
}

TEST(MeshContact, ContactBeginsOnlyThroughTheOutside) {
  {
    const MeshSurface surface(flat_panel());
    MeshContact contact(surface, kParams);
    Path path(Vector3d(16, -12, -5));
    path.to({16, -12, -1}, 50).to({16, -12, 2}, 50);  // behind, then out through the panel from behind
    ASSERT_GT(crossings(surface, path), 0);  // it does pass through the sheet
    for (const MeshTouch& t : run(contact, path)) {
      ASSERT_FALSE(t.contact);
      ASSERT_EQ(t.force_N, Vector3d::Zero());
    }
    Path in(Vector3d(16, -12, 2));
    in.to({16, -12, -1}, 50);  // in from the front: 1 mm deep, pressing at 50 mm/s
    const std::vector<MeshTouch> touches = run(contact, in);
    EXPECT_TRUE(touches.back().contact);
    EXPECT_NEAR(touches.back().force_N.z(), kK * 1.0 + kB * 0.05, 1e-12);
    MeshContact sideways(surface, kParams);
    Path under(Vector3d(36, -12, -3));
    under.to({20, -12, -3}, 50);  // from past the right edge, under the panel
    for (const MeshTouch& t : run(sideways, under)) ASSERT_FALSE(t.contact);
  }
  {
    // The curl at u = 0.5 opens at its back (no sheet between 90° and 230° round from its top): its
    // axis is at y = −1.5, z = 2; its front wall, at v = 0.41, faces the endoscope (+z) at z ≈ 7.85.
    const MeshSurface surface(load_tissue_mesh(test::source_dir() + "/scenarios/meshes/turbinate.obj"));
    const Vector3d front = turbinate_point(0.5, 0.41), axis(20, -1.5, 2);
    ASSERT_GT(turbinate_normal(0.5, 0.41).z(), 0.99);
    MeshContact contact(surface, kParams);
    Path path(Vector3d(20, front.y(), -15));
    path.to({20, front.y(), axis.z()}, 50)          // in through the open back
        .to({20, front.y(), front.z() + 2}, 50);    // out through the front wall from inside
    ASSERT_GT(crossings(surface, path), 0);  // it does pass through the sheet
    for (const MeshTouch& t : run(contact, path)) ASSERT_FALSE(t.contact);
    Path back(Vector3d(20, front.y(), front.z() + 2));
    back.to({20, front.y(), front.z() - 1}, 50);    // in through the front wall from outside
    const std::vector<MeshTouch> touches = run(contact, back);
    EXPECT_TRUE(touches.back().contact);
    EXPECT_NEAR(touches.back().penetration_mm, 1.0, 0.05);  // the facets lie within 0.05 mm of the curl
    EXPECT_GT(touches.back().force_N.z(), 0.0);
  }
}
}  // namespace
}  // namespace bleedsim
