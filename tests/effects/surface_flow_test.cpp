// Blood on a tissue mesh (core/physics/surface.h): particles move and measure in surface
// millimetres. On a tilted plane a lone particle's acceleration is g·sin(slope); on a tilted
// cylinder blood runs down the steepest descent wherever it goes; and a flat mesh reproduces the
// flat panel's every field, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/io/scenario.h"
#include "core/simulation/simulation.h"
#include "tests/effects/particle_box.h"
#include "tests/mesh/meshes_in_code.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

constexpr double kDegree = M_PI / 180.0;

// A lone particle's world: no grip (it would only slow it), the default drag and gravity.
Scene lone_particle_scene(double width_mm, double height_mm, int width_px, int height_px) {
  ParticleParams p;
  p.pinning_mm3_s2 = p.yield_mm2_s2 = 0.0;
  Scene scene = test::box_scene(width_mm, height_mm, p);
  scene.domain.width_px = width_px;
  scene.domain.height_px = height_px;
  return scene;
}

TEST(SurfaceFlow, OnATiltedPlaneALoneParticleFallsAtGSinTheSlope) {
  // The 32 × 24 mm panel made at twice its size (scale 2: a panel mm is 2 surface mm), turned
  // about the device's x by θ, then about its z by φ. Its normal is R·ẑ = (sin φ sin θ, −cos φ sin θ,
  // cos θ), so its slope α from the horizontal has cos α = cos φ sin θ, and gravity along it is
  // g·sin α, along R·(0, −1, 0) and R·x̂ with components (−g sin φ, g cos φ cos θ).
  // Semi-implicit Euler with implicit drag γ from rest: v_n = (g_t/γ)(1 − qⁿ), q = 1/(1 + γ·dt),
  // and the distance travelled Σ dt·v_k (k = 1 … n). Measured on the surface (2 × the panel's
  // displacement) both agree with the closed form for g·sin α to float rounding over n steps,
  // ~n·2⁻²⁴ relative; the 0.1 % is far above that.
  for (const auto& [theta_deg, phi_deg] : {std::pair{55.0, 0.0}, std::pair{20.0, 30.0}, std::pair{80.0, -60.0}}) {
    Scene scene = lone_particle_scene(32.0, 24.0, 64, 48);
    MeshPlacement at;
    at.rotation_deg = Eigen::Vector3d(theta_deg, 0.0, phi_deg);
    at.scale = 2.0;
    scene.mesh = std::make_shared<const MeshSurface>(placed(test::flat_panel_mesh(32.0, 24.0), at));
    test::ParticleBox box(scene, {{12.0, 6.0}});
    const double theta = theta_deg * kDegree, phi = phi_deg * kDegree,
                 g = scene.effects.get<ParticleParams>().gravity_y_mm_s2;
    const double slope = std::acos(std::cos(phi) * std::sin(theta));
    const double gx = -g * std::sin(phi), gy = g * std::cos(phi) * std::cos(theta);
    ASSERT_NEAR(std::hypot(gx, gy), g * std::sin(slope), 1e-9 * g);
    const double gamma = scene.effects.get<ParticleParams>().drag_per_s, dt = box.dt(), q = 1.0 / (1.0 + gamma * dt);
    const long n = std::lround(0.02 / dt);  // 20 ms: two time constants, 2 mm at most
    double travelled = 0.0;
    for (long k = 1; k <= n; ++k) travelled += dt * (1.0 - std::pow(q, double(k)));
    travelled *= std::sin(slope) * g / gamma;
    box.run_for(n * dt);
    const test::Point moved{2.0 * (box.position(0).x - 12.0), 2.0 * (box.position(0).y - 6.0)};
    const double speed = box.speed(0), expected_speed = g * std::sin(slope) / gamma * (1.0 - std::pow(q, double(n)));
    const double acceleration = speed * gamma / (1.0 - std::pow(q, double(n)));
    std::cout << "slope " << slope / kDegree << "°: acceleration " << acceleration << " mm/s² (g·sin α = "
              << g * std::sin(slope) << "), travelled " << std::hypot(moved.x, moved.y) << " mm (closed form "
              << travelled << ")\n";
    EXPECT_NEAR(acceleration, g * std::sin(slope), 1e-3 * g * std::sin(slope));
    EXPECT_NEAR(speed, expected_speed, 1e-3 * expected_speed);
    EXPECT_NEAR(std::hypot(moved.x, moved.y), travelled, 1e-3 * travelled);
    // And along gravity's direction on the surface.
    EXPECT_NEAR(std::atan2(moved.y, moved.x), std::atan2(gy, gx), 1e-3);
  }
}

// A trough: a cylinder of radius R about the device's x axis from θ = −100° to 100° around its
// lowest line (uv = (along, around)), n facets around, its axis then tilted down by β along +x.
struct Trough {
  double length_mm = 60.0, radius_mm = 10.0, half_arc = 100.0 * kDegree, tilt = 30.0 * kDegree;
  int facets = 512;

  double arc_mm() const { return 2.0 * half_arc * radius_mm; }
  Eigen::Matrix3d turn() const { return Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
  // The smooth surface at (u, v), and its normal there.
  Eigen::Vector3d point(double u, double v) const {
    const double around = -half_arc + 2.0 * half_arc * v;
    return turn() * Eigen::Vector3d(length_mm * u, -radius_mm * std::cos(around), radius_mm * std::sin(around));
  }
  Eigen::Vector3d normal(double v) const {
    const double around = -half_arc + 2.0 * half_arc * v;
    return turn() * Eigen::Vector3d(0.0, -std::cos(around), std::sin(around));
  }
  TissueMesh mesh() const {
    return test::parametric_mesh(8, facets, [&](double u, double v) { return point(u, v); });
  }
};

TEST(SurfaceFlow, OnATiltedCylinderBloodRunsDownTheSteepestDescent) {
  // Lone particles let go on the trough's sides run down towards its lowest line and along it.
  // Each step, a particle's velocity on the surface (its components along the trough's axis and
  // around it) is compared with the steepest descent where it is, g − (g·n)n on the smooth trough.
  // (Its move in one step is a few float ulps of its position, too coarse for a direction.)
  // The bound: (1) the velocity follows the steepest descent as a first-order lag (time constant
  // 1/γ, and dt more for the discrete step): where that direction turns at κ per mm of path and the
  // particle moves at v ≤ g/γ, the lag angle is atan(κ·v·(1/γ + dt)). Around a trough tilted by β
  // the direction's angle from the axis is ψ with tan ψ = cot β · sin(around), which turns fastest
  // on the lowest line, dψ/ds = cot β / R. (2) Facets and texels: a texel takes the facet under its
  // centre, up to half a texel (Δ) from the particle and half a facet (δ/2) more from the smooth
  // surface's tangent plane, which turns the steepest descent by at most
  // atan(cos β sin(Δ/2 + δ/2) / sin β), where gravity along the surface is least (the lowest line),
  // and the facet's frame turns the velocity from the smooth surface's by at most δ/2 + Δ/2 more.
  const Trough trough;
  const int width_px = 600, height_px = 700;
  Scene scene = lone_particle_scene(trough.length_mm, trough.arc_mm(), width_px, height_px);
  scene.mesh = std::make_shared<const MeshSurface>(trough.mesh());
  const double g = scene.effects.get<ParticleParams>().gravity_y_mm_s2,
               gamma = scene.effects.get<ParticleParams>().drag_per_s;
  const Eigen::Vector3d gravity = device_gravity_mm_s2(scene), axis = trough.turn() * Eigen::Vector3d::UnitX();
  const double facet = 2.0 * trough.half_arc / trough.facets, texel = 2.0 * trough.half_arc / height_px;
  const double beta = trough.tilt, tilt = (facet + texel) / 2.0;
  double bound = 0.0;
  for (const double v0 : {0.1, 0.25, 0.75, 0.92}) {
    test::ParticleBox box(scene, {{0.15 * trough.length_mm, v0 * trough.arc_mm()}});
    const double dt = box.dt(), kappa = 1.0 / (std::tan(beta) * trough.radius_mm);
    bound = std::atan(kappa * (g / gamma) * (1.0 / gamma + dt)) +
            std::atan(std::cos(beta) * std::sin(tilt) / std::sin(beta)) + tilt;
    double worst = 0.0;
    long compared = 0;
    for (long step = 0; step < std::lround(5.0 / dt); ++step) {
      box.step();
      const double v = box.position(0).y / trough.arc_mm();
      const double around = -trough.half_arc + 2.0 * trough.half_arc * v;
      const Eigen::Vector3d across = trough.turn() * Eigen::Vector3d(0.0, std::sin(around), std::cos(around));
      const Eigen::Vector3d velocity = box.velocity(0).x * axis + box.velocity(0).y * across;
      if (velocity.norm() < 1e-3) continue;  // at rest: no direction to compare
      const Eigen::Vector3d n = trough.normal(v), descent = gravity - gravity.dot(n) * n;
      worst = std::max(worst, std::acos(std::clamp(velocity.normalized().dot(descent.normalized()), -1.0, 1.0)));
      ++compared;
    }
    const double u_end = box.position(0).x / trough.length_mm, v_end = box.position(0).y / trough.arc_mm();
    std::cout << "from " << (v0 - 0.5) * 200.0 << "° around: " << compared << " steps, the worst angle to the "
              << "steepest descent " << worst / kDegree << "° (bound " << bound / kDegree << "°), ended at u = "
              << u_end << ", v = " << v_end << "\n";
    EXPECT_GT(compared, 10000);
    EXPECT_LE(worst, bound);
    // In 5 s (4 of the approach's time constants, R·γ / (g cos β)) it came down to within 2° of the
    // lowest line and ran along it.
    EXPECT_NEAR(v_end, 0.5, 2.0 / 200.0);
    EXPECT_GT(u_end, 0.15 + 0.3);
  }
  EXPECT_LT(bound, 2.0 * kDegree);  // the 2°
}

// Every field of every frame of `scene` with and without `mesh`, byte for byte: the surface's own
// fields aside.
void expect_the_same_run(Scene scene, const TissueMesh& mesh, int frames) {
  Scene on_mesh = scene;
  on_mesh.mesh = std::make_shared<const MeshSurface>(mesh);
  Simulation flat(scene, BackendChoice{BackendChoice::Want::cpu, 2});
  Simulation curved(on_mesh, BackendChoice{BackendChoice::Want::cpu, 2});
  ASSERT_EQ(curved.field_names().size(), flat.field_names().size() + 2);
  for (int f = 0; f < frames; ++f) {
    flat.step();
    curved.step();
    for (const std::string& name : flat.field_names())
      ASSERT_EQ(flat.copy_field(name), curved.copy_field(name)) << scene.name << ": frame " << f << ", " << name;
  }
}

TEST(SurfaceFlow, AFlatMeshReproducesTheFlatPanelToTheBit) {
  // The panel as a mesh at its own size has the identity frame to the bit (SurfaceBake), and every
  // conversion through it is then exact (core/physics/surface.h): the same bytes, frame by frame.
  // The golden scenes without a stylus: spread, particles, blur, trail, optics, vessels, pulse.
  for (const char* name : {"composite-blur", "particles-stream", "particles-every-step", "spread-overlap",
                           "optics-trails", "vessels-pulse"}) {
    const Scene scene = load_scenario(test::source_dir() + "/scenarios/golden/" + name + ".toml").scene;
    expect_the_same_run(scene, test::flat_panel_mesh(scene.domain.width_mm, scene.domain.height_mm),
                        std::min(scene.frame_count(), 45));
  }
}

}  // namespace
}  // namespace bleedsim