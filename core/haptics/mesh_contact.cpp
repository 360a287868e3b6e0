#include "core/haptics/mesh_contact.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace bleedsim {
namespace {

// A tick's walk crosses a few triangles; this many steps means something is wrong, and the proxy
// settles where the walk got to.
constexpr int kMaxWalk = 1024;
// Newton's iterations for the proxy on a triangle or an edge: from the flat solution, two or three
// reach rounding on meshes whose normals turn a little over a triangle.
constexpr int kMaxNewton = 32;

// One Newton step for r(y) = 0 with Jacobian j; false when j is singular (the device past the depth
// at which neighbouring normals cross) or the step is not finite.
bool newton_step(Eigen::Vector3d& y, const Eigen::Vector3d& r, const Eigen::Matrix3d& j, double scale,
                 bool& converged) {
  const double det = j.determinant();
  if (!(std::fabs(det) > 1e-12 * scale)) return false;
  const Eigen::Vector3d step = j.inverse() * r;
  if (!step.allFinite()) return false;
  y -= step;
  converged = step.cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + y.cwiseAbs().maxCoeff());
  return true;
}

}  // namespace

struct MeshContact::Found {
  SurfacePoint at;
  Eigen::Vector3d normal;
  double penetration_mm = 0.0;
  double beyond_mm = 0.0;
};

struct MeshContact::EdgeSolution {
  double t = 0.0;          // along the edge, 0 at its first end, 1 at its second
  double beyond_mm = 0.0;  // past the edge in the tangent plane, away from the triangle (< 0: over it)
};

MeshContact::MeshContact(const MeshSurface& surface, const HapticParams& params)
    : surface_(surface),
      stiffness_N_per_m_(params.stiffness_N_per_m),
      damping_Ns_per_m_(params.damping_Ns_per_m),
      max_force_N_(params.max_force_N),
      device_damping_Ns_per_m_(params.device_damping_Ns_per_m) {
  if (const ParamProblem problem = passivity_problem(params)) throw std::invalid_argument(problem.text());
  const TissueMesh& mesh = surface.mesh();
  const int triangles = int(mesh.triangles.size());

  // Outward normals. With (u, v) the texture's coordinates and e1, e2 the triangle's edges from its
  // first corner, [e1 e2] = [∂P/∂u ∂P/∂v]·[Δuv1 Δuv2], so ∂P/∂v × ∂P/∂u = −(e1 × e2) / det[Δuv1 Δuv2]:
  // the winding's normal, turned over where the texture's triangle runs counter-clockwise.
  // Each vertex's normal is the sum of its triangles' outward normals weighted by their areas,
  // Σ ½|e1 × e2|·n, normalised.
  face_normals_.resize(triangles);
  vertex_normals_.assign(mesh.positions.size(), Eigen::Vector3d::Zero());
  for (int t = 0; t < triangles; ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d e1 = corner(t, 1) - corner(t, 0), e2 = corner(t, 2) - corner(t, 0);
    const Eigen::Vector2d d1 = mesh.uvs[tri.uv[1]] - mesh.uvs[tri.uv[0]];
    const Eigen::Vector2d d2 = mesh.uvs[tri.uv[2]] - mesh.uvs[tri.uv[0]];
    const double uv_det = d1.x() * d2.y() - d2.x() * d1.y();
    const Eigen::Vector3d area_normal = (uv_det > 0 ? -0.5 : 0.5) * e1.cross(e2);  // |·| = the area
    face_normals_[t] = area_normal.normalized();
    for (int k = 0; k < 3; ++k) vertex_normals_[tri.corner[k]] += area_normal;
  }
  // A vertex whose triangles' normals cancel has no direction: zero, and the shading falls back to
  // the face's normal where its weight would matter (shading_normal).
  for (Eigen::Vector3d& n : vertex_normals_) n = n.norm() > 0 ? n.normalized() : Eigen::Vector3d::Zero();

  // Neighbours across each edge (edge k is opposite corner k), and each vertex's boundary edges.
  std::vector<std::tuple<int, int, int, int>> edges;  // (lower vertex, higher vertex, triangle, edge)
  for (int t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles[t].corner[(k + 1) % 3], b = mesh.triangles[t].corner[(k + 2) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b), t, k);
    }
  std::sort(edges.begin(), edges.end());
  neighbours_.assign(triangles, {-1, -1, -1});
  boundary_at_.assign(mesh.positions.size(), {});
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
           std::get<1>(edges[j]) == std::get<1>(edges[i]))
      ++j;
    if (j - i == 2) {  // the mesh reader allows at most two triangles an edge
      neighbours_[std::get<2>(edges[i])][std::get<3>(edges[i])] = std::get<2>(edges[i + 1]);
      neighbours_[std::get<2>(edges[i + 1])][std::get<3>(edges[i + 1])] = std::get<2>(edges[i]);
    } else if (j - i == 1) {
      const std::array<int, 2> edge{std::get<2>(edges[i]), std::get<3>(edges[i])};
      boundary_at_[std::get<0>(edges[i])].push_back(edge);
      boundary_at_[std::get<1>(edges[i])].push_back(edge);
    }
    i = j;
  }
}

Eigen::Vector3d MeshContact::corner(int triangle, int k) const {
  const TissueMesh& mesh = surface_.mesh();
  return mesh.positions[mesh.triangles[triangle].corner[k]];
}

const Eigen::Vector3d& MeshContact::corner_normal(int triangle, int k) const {
  return vertex_normals_[surface_.mesh().triangles[triangle].corner[k]];
}

Eigen::Vector3d MeshContact::shading_normal(const SurfacePoint& at) const {
  const Eigen::Vector3d n = at.barycentric[0] * corner_normal(at.triangle, 0) +
                            at.barycentric[1] * corner_normal(at.triangle, 1) +
                            at.barycentric[2] * corner_normal(at.triangle, 2);
  const double length = n.norm();
  return length > 1e-9 ? Eigen::Vector3d(n / length) : face_normals_[at.triangle];
}

// (triangle, device) => the weights w of the point P(w) of the triangle's plane, w extended past
// its edges, whose shading normal passes through the device: device = P(w) − h·N(w), with
// P(w) = p0 + w1·e1 + w2·e2 and N(w) = n0 + w1·m1 + w2·m2 the corners' normals interpolated (not
// normalised: the same line). Newton on (w1, w2, h) from the solution with N held at the centroid's
// (exact at once where the corners' normals agree); none when the Jacobian is singular, where the
// device is so deep that the normal lines of neighbouring points cross.
std::optional<Eigen::Vector3d> MeshContact::phong_weights(int triangle, const Eigen::Vector3d& x) const {
  const Eigen::Vector3d p0 = corner(triangle, 0);
  const Eigen::Vector3d e1 = corner(triangle, 1) - p0, e2 = corner(triangle, 2) - p0;
  const Eigen::Vector3d& n0 = corner_normal(triangle, 0);
  const Eigen::Vector3d m1 = corner_normal(triangle, 1) - n0, m2 = corner_normal(triangle, 2) - n0;
  if (n0.isZero() || (m1 + n0).isZero() || (m2 + n0).isZero()) return std::nullopt;  // no shading here
  const double scale = e1.norm() * e2.norm();
  Eigen::Matrix3d j;
  j << e1, e2, -(n0 + (m1 + m2) / 3.0);
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  bool converged = false;
  if (!newton_step(y, -(x - p0), j, scale, converged)) return std::nullopt;
  for (int iteration = 0; iteration < kMaxNewton && !converged; ++iteration) {
    const Eigen::Vector3d n = n0 + y[0] * m1 + y[1] * m2;
    const Eigen::Vector3d r = y[0] * e1 + y[1] * e2 - y[2] * n - (x - p0);
    j << e1 - y[2] * m1, e2 - y[2] * m2, -n;
    if (!newton_step(y, r, j, scale, converged)) return std::nullopt;
  }
  if (!converged) return std::nullopt;
  return Eigen::Vector3d(1.0 - y[0] - y[1], y[0], y[1]);
}

// (triangle, edge, device) => the edge's point whose shading normal, with the edge's outward
// direction in the tangent plane, reaches the device: device = P(t) − h·N(t) + s·o(t), with P(t) and
// N(t) the edge's points and normals, o(t) = ±ê × N(t) pointing away from the triangle. s is how far
// past the edge the device lies in the tangent plane there; at s = 0 this is phong_weights' solution
// on the edge, so the proxy moves continuously from the face onto its boundary.
std::optional<MeshContact::EdgeSolution> MeshContact::phong_edge(int triangle, int edge,
                                                                 const Eigen::Vector3d& x) const {
  const int ka = (edge + 1) % 3, kb = (edge + 2) % 3;
  const Eigen::Vector3d pa = corner(triangle, ka), e = corner(triangle, kb) - pa;
  const Eigen::Vector3d& na = corner_normal(triangle, ka);
  const Eigen::Vector3d m = corner_normal(triangle, kb) - na;
  const Eigen::Vector3d unit = e.normalized();
  // Away from the triangle: from the edge, the opposite corner lies on the other side.
  const double away = unit.cross(face_normals_[triangle]).dot(corner(triangle, edge) - pa) > 0 ? -1.0 : 1.0;
  const auto normal_at = [&](double t) -> Eigen::Vector3d { return na + t * m; };
  const auto out_at = [&](double t) -> Eigen::Vector3d { return away * unit.cross(normal_at(t)); };
  // Start from the device's foot on the edge's line.
  const double t0 = (x - pa).dot(e) / e.squaredNorm();
  const Eigen::Vector3d n_start = normal_at(t0), o_start = out_at(t0);
  if (n_start.isZero() || o_start.isZero()) return std::nullopt;
  Eigen::Vector3d y(t0, (pa + t0 * e - x).dot(n_start) / n_start.squaredNorm(),
                    (x - pa - t0 * e).dot(o_start) / o_start.squaredNorm());
  bool converged = false;
  for (int iteration = 0; iteration < kMaxNewton && !converged; ++iteration) {
    const Eigen::Vector3d n = normal_at(y[0]), o = out_at(y[0]);
    const Eigen::Vector3d r = pa + y[0] * e - y[1] * n + y[2] * o - x;
    Eigen::Matrix3d j;
    j << e - y[1] * m + y[2] * away * unit.cross(m), -n, o;
    if (!newton_step(y, r, j, e.norm(), converged)) return std::nullopt;
  }
  if (!converged) return std::nullopt;
  return EdgeSolution{y[0], y[2] * out_at(y[0]).norm()};
}

// (triangle, weights, device) => the proxy there: its point, shading normal, and the device's depth
// behind it along that normal.
MeshContact::Found MeshContact::found_at(int triangle, const Eigen::Vector3d& w, double beyond_mm,
                                         const Eigen::Vector3d& x) const {
  Found found;
  found.at.triangle = triangle;
  found.at.barycentric = w;
  // From the first corner, so that a flat mesh's points keep its corners' coordinate exactly.
  const Eigen::Vector3d p0 = corner(triangle, 0);
  found.at.point = p0 + w[1] * (corner(triangle, 1) - p0) + w[2] * (corner(triangle, 2) - p0);
  found.at.distance_mm = (x - found.at.point).norm();
  found.normal = shading_normal(found.at);
  found.penetration_mm = (found.at.point - x).dot(found.normal);
  found.beyond_mm = beyond_mm;
  return found;
}

MeshContact::Found MeshContact::on_edge(int triangle, int edge, double t, double beyond_mm,
                                        const Eigen::Vector3d& x) const {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  w[(edge + 1) % 3] = 1.0 - t;
  w[(edge + 2) % 3] = t;
  return found_at(triangle, w, beyond_mm, x);
}

std::optional<std::array<int, 2>> MeshContact::next_boundary_edge(int triangle, int edge, int vertex) const {
  const auto& at = boundary_at_[vertex];
  if (at.size() != 2) return std::nullopt;  // a vertex where more than one piece of boundary meets
  return at[0] == std::array<int, 2>{triangle, edge} ? at[1] : at[0];
}

// (device, the previous proxy's triangle) => the proxy this tick. A walk over neighbouring
// triangles: on each, the point whose shading normal passes through the device; while that point
// falls past an edge, on to the triangle across it. Past a boundary edge the proxy follows the
// boundary (along the edge, round a corner onto the next boundary edge, or onto the corner itself)
// and the tissue continues as the tangent plane there. A walk never goes back to a face or edge it
// has left this tick: where it would (the device so deep that the normal lines of both sides cross),
// the proxy settles on the edge between them.
MeshContact::Found MeshContact::follow(const Eigen::Vector3d& x, int start) const {
  std::vector<std::array<int, 2>> visited;  // (triangle, −1): a face; (triangle, k): its boundary edge k
  const auto seen = [&](int t, int k) {
    return std::find(visited.begin(), visited.end(), std::array<int, 2>{t, k}) != visited.end();
  };
  const auto nearest = [&](int t) {  // where the shading cannot be solved: the triangle's nearest point
    const Eigen::Vector3d w = closest_on_triangle(x, corner(t, 0), corner(t, 1), corner(t, 2));
    return found_at(t, w, 0.0, x);
  };
  int triangle = start, edge = -1;
  for (int step = 0; step < kMaxWalk; ++step) {
    visited.push_back({triangle, edge});
    if (edge < 0) {
      // On a face: inside it, the proxy is found; past an edge, on across it, unless there is no
      // triangle there or the walk came from it.
      const std::optional<Eigen::Vector3d> w = phong_weights(triangle, x);
      if (!w) return nearest(triangle);
      int k = 0;
      if (w->minCoeff(&k) >= 0) return found_at(triangle, *w, 0.0, x);
      const int next = neighbours_[triangle][k];
      if (next >= 0 && !seen(next, -1)) {
        triangle = next;
      } else {
        edge = k;
      }
      continue;
    }
    // On an edge: between two faces the walk turned back on, the proxy stays on it.
    const std::optional<EdgeSolution> on = phong_edge(triangle, edge, x);
    if (!on) return nearest(triangle);
    if (neighbours_[triangle][edge] >= 0) return on_edge(triangle, edge, std::clamp(on->t, 0.0, 1.0), 0.0, x);
    // A boundary edge. The device back over the face: onto the face, if the walk has not been there.
    if (on->beyond_mm < 0 && !seen(triangle, -1)) {
      edge = -1;
      continue;
    }
    const double beyond_mm = std::max(on->beyond_mm, 0.0);
    if (on->t >= 0 && on->t <= 1) return on_edge(triangle, edge, on->t, beyond_mm, x);
    // Past one end of the edge: onto the boundary's next edge there, or, where the device lies past
    // both, the corner itself: the tissue continues as the corner's tangent plane.
    const int k = on->t < 0 ? (edge + 1) % 3 : (edge + 2) % 3;
    const int vertex = surface_.mesh().triangles[triangle].corner[k];
    const std::optional<std::array<int, 2>> next = next_boundary_edge(triangle, edge, vertex);
    if (next && !seen((*next)[0], (*next)[1])) {
      triangle = (*next)[0];
      edge = (*next)[1];
      continue;
    }
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    w[k] = 1.0;
    Found found = found_at(triangle, w, 0.0, x);
    const Eigen::Vector3d off = x - found.at.point;
    found.beyond_mm = (off - off.dot(found.normal) * found.normal).norm();
    return found;
  }
  return nearest(triangle);
}

MeshTouch MeshContact::touch(const Eigen::Vector3d& x) {
  MeshTouch touch;
  touch.proxy.point = x;

  // Where the proxy is: followed from the last tick's while in contact; otherwise, contact begins only
  // where the tip passed through a triangle from its outside since the last tick (a tip that is
  // merely behind the surface, having come round its edge or from behind it, touches nothing).
  std::optional<Found> found;
  if (proxy_) {
    found = follow(x, proxy_->triangle);
  } else if (previous_mm_) {
    for (const SegmentCrossing& crossing : surface_.crossings(*previous_mm_, x))
      if ((x - *previous_mm_).dot(face_normals_[crossing.at.triangle]) < 0) {
        found = follow(x, crossing.at.triangle);
        break;
      }
  }

  // In contact while the device is behind the proxy's tangent plane. The force along the shading
  // normal: a spring on the penetration and a damper on the tip's speed along the normal (a backward
  // difference over one tick), pushing, never pulling, and no more than the device can; then no more
  // than the energy bound allows (the header's last block).
  if (found && found->penetration_mm > 0) {
    const Eigen::Vector3d step_m = previous_mm_ ? Eigen::Vector3d((x - *previous_mm_) / 1000.0) : Eigen::Vector3d::Zero();
    reserve_J_ += device_damping_Ns_per_m_ * step_m.squaredNorm() / kHapticPeriod_s - held_N_.dot(step_m);
    touch.contact = true;
    touch.proxy = found->at;
    touch.penetration_mm = found->penetration_mm;
    touch.beyond_edge_mm = found->beyond_mm;
    touch.normal = found->normal;
    touch.reserve_J = reserve_J_;
    const double normal_speed_m_s = found->normal.dot(step_m) / kHapticPeriod_s;
    const double push_N =
        stiffness_N_per_m_ * found->penetration_mm / 1000.0 - damping_Ns_per_m_ * normal_speed_m_s;
    const double bound_N = std::sqrt(std::max(0.0, 4.0 * device_damping_Ns_per_m_ * reserve_J_ / kHapticPeriod_s));
    touch.force_N = std::min({std::max(push_N, 0.0), max_force_N_, bound_N}) * found->normal;
    proxy_ = found->at;
  } else {
    proxy_.reset();
    reserve_J_ = 0.0;
  }
  held_N_ = touch.force_N;
  previous_mm_ = x;
  return touch;
}

}  // namespace bleedsim
