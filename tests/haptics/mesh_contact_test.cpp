// The stylus' contact with a tissue mesh (core/haptics/mesh_contact.h): the flat mesh against the
// plane of the haptic loop, force continuity past the mesh's boundary and across creases, no
// tunnelling through the curled turbinate, and contact that begins only by passing through the
// surface from outside (its energy: mesh_contact_passivity_test.cpp). Every bound is derived in the
// comment above its test from the spring, the damper, the sweep's step and the normal field's turn;
// the reference values come from closed forms written here and in mesh_contact_geometry.h, not from
// the code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "core/haptics/mesh_contact.h"
#include "tests/haptics/mesh_contact_geometry.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

using namespace test;

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
