#pragma once
// The stylus' contact with a tissue mesh (docs/haptics.md, "Contact with a tissue mesh"): a
// god-object proxy (Zilles & Salisbury 1995) that stays on the surface, a spring and a damper between
// the device and the proxy along a smooth normal (force shading, Morgenbesser & Srinivasan 1996), so
// that the force is continuous over edges, creases and the mesh's boundary.
//
// One call a 1 kHz tick, host code only. Conventions:
// - The device frame is the Falcon's (x right, y up, z towards the user), in millimetres; the mesh
//   is already placed in it.
// - A triangle's outside (the side the endoscope and the stylus come from) is the side from which
//   its texture reads the right way round: its outward normal is ∂P/∂v × ∂P/∂u normalised (v runs
//   down the texture's rows), whatever the winding. The flat panel's is +z.
// - The tissue lies behind its surface. Contact begins only when the tip passes through a triangle
//   from its outside; it ends when the tip is back in front of the proxy's tangent plane.
//
// The model, block by block in mesh_contact.cpp:
// - The proxy stays on the surface near where it was: each tick it walks from the previous proxy's
//   triangle across neighbouring triangles to the point P whose shading normal passes through the
//   device, device = P − h·n(P): the condition for the nearest point of a smooth surface with the
//   shading's normals, and on a triangle whose corners' normals agree its nearest point. (The facets'
//   own nearest point jumps across a convex crease's bisector, and the force's direction with it.) It
//   never jumps to another part of the mesh, so a curled sheet is not tunnelled through.
// - n(P) is the area-weighted vertex normals interpolated by P's barycentric weights and normalised:
//   continuous across edges and creases, so the force's direction does not jump there.
// - Past the mesh's boundary (an edge with one triangle) the proxy stays on the boundary and the
//   tissue continues as its tangent plane there: the force does not drop as the tip slides past the
//   edge, and falls to zero as the tip rises out.
// - The force: f = clamp(k·h − b·v_n, 0, f_max) along n, v_n = n·(x_n − x_{n−1}) / T, the plane's
//   formula of HapticLoop (which it equals on the flat panel). Sampled at 1 kHz it is passive under
//   the same bound (Colgate & Schenkel); but force shading's field is not conservative: around a loop
//   it does ∮ k·h·n·dP, up to k·h·sin τ a mm of the proxy's path (τ the shading's tilt from the
//   facet), whatever the speed — docs/haptics.md gives the figures.
// - So the force is bounded by the energy the contact has taken in (energy bounding, Kim & Ryu 2004).
//   Over a contact, the reserve R = D − W is what the device's own damping B has dissipated,
//   D = Σ B·|Δx|²/T, less the work the held forces have done on the device, W = Σ F·Δx. Whatever the
//   hand does in the coming tick, holding F changes R by B·|Δx|²/T − F·Δx ≥ −T·|F|²/(4B) (the
//   quadratic's least value), so |F| ≤ √(4B·R/T) keeps R ≥ 0: W ≤ D at every tick of every contact,
//   which is passivity with the device's damping (Colgate & Schenkel's condition, here for any field).
//   A spring leaves R ≥ ½k·h², which the bound's T·(k·h)²/(4B) stays below when B > k·T/2: the flat
//   panel's plane never meets it in the tests (test 1 of tests/haptics/mesh_contact_test.cpp); force
//   shading meets it where it would return energy.
#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/haptics/haptic_params.h"
#include "core/mesh/mesh_surface.h"

namespace bleedsim {

// What one tick of the contact found.
struct MeshTouch {
  bool contact = false;
  // The proxy. In contact: on the surface (its triangle and weights give its texel through
  // MeshSurface::uv; distance_mm from the device). Out of contact: the device's own position, on no
  // triangle (−1).
  SurfacePoint proxy;
  double penetration_mm = 0.0;   // the device behind the proxy along the normal, h (0 out of contact)
  double beyond_edge_mm = 0.0;   // how far past the mesh's boundary, in its tangent plane (0 over it)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();   // n at the proxy, unit (zero out of contact)
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();  // on the device, device frame
  // The energy bound's reserve R = D − W over this contact up to this tick, J (0 out of contact);
  // |force_N| ≤ √(4B·R/T).
  double reserve_J = 0.0;
};

class MeshContact {
 public:
  // Keeps a reference to `surface`, which must outlive the contact, and the contact parameters of
  // `params` (stiffness_N_per_m, damping_Ns_per_m, max_force_N, device_damping_Ns_per_m). Throws std::invalid_argument when
  // they are not passive at 1 kHz (passivity_problem).
  MeshContact(const MeshSurface& surface, const HapticParams& params);

  // One tick: the device's tip in the device frame, mm. The first tick only records where it is.
  MeshTouch touch(const Eigen::Vector3d& device_mm);

  // The outward normal of a triangle (unit).
  const Eigen::Vector3d& face_normal(int triangle) const { return face_normals_[triangle]; }
  // The area-weighted normal of a vertex (an index into the mesh's positions; unit).
  const Eigen::Vector3d& vertex_normal(int vertex) const { return vertex_normals_[vertex]; }
  // The shading normal at a point of the surface: its corners' normals by its weights, normalised.
  Eigen::Vector3d shading_normal(const SurfacePoint& at) const;

 private:
  struct Found;         // where the proxy settled this tick
  struct EdgeSolution;  // the proxy on one edge: where along it, how far past it
  Found follow(const Eigen::Vector3d& device_mm, int triangle) const;
  std::optional<Eigen::Vector3d> phong_weights(int triangle, const Eigen::Vector3d& device_mm) const;
  std::optional<EdgeSolution> phong_edge(int triangle, int edge, const Eigen::Vector3d& device_mm) const;
  Found found_at(int triangle, const Eigen::Vector3d& weights, double beyond_mm, const Eigen::Vector3d& device_mm) const;
  Found on_edge(int triangle, int edge, double t, double beyond_mm, const Eigen::Vector3d& device_mm) const;
  std::optional<std::array<int, 2>> next_boundary_edge(int triangle, int edge, int vertex) const;
  Eigen::Vector3d corner(int triangle, int k) const;
  const Eigen::Vector3d& corner_normal(int triangle, int k) const;

  const MeshSurface& surface_;
  double stiffness_N_per_m_, damping_Ns_per_m_, max_force_N_, device_damping_Ns_per_m_;
  std::vector<Eigen::Vector3d> face_normals_;
  std::vector<Eigen::Vector3d> vertex_normals_;
  std::vector<std::array<int, 3>> neighbours_;  // across the edge opposite each corner; −1 on the boundary
  std::vector<std::vector<std::array<int, 2>>> boundary_at_;  // per vertex: its boundary edges (triangle, edge)

  std::optional<Eigen::Vector3d> previous_mm_;  // the device at the last tick
  std::optional<SurfacePoint> proxy_;           // the proxy while in contact
  double reserve_J_ = 0.0;                       // the energy bound's R, this contact so far
  Eigen::Vector3d held_N_ = Eigen::Vector3d::Zero();  // the force sent at the last tick
};

}  // namespace bleedsim
