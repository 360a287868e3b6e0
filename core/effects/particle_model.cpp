#include "core/effects/particle_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/physics/splat.h"

namespace bleedsim {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

double cell_edge_mm(const ParticleParams& p) { return p.cell_mm > 0.0 ? p.cell_mm : p.diameter_mm; }

int cells_along(double panel_mm, double cell_mm) {
  return std::max(1, int(std::ceil(panel_mm / cell_mm)));
}

std::uint32_t steps_in(double seconds, double steps_per_s) {
  return std::uint32_t(std::max(1.0, std::round(seconds * steps_per_s)));
}

int bits_for(std::uint32_t value) {
  int bits = 0;
  while (bits < 32 && (value >> bits) != 0) ++bits;
  return std::max(bits, 1);
}

}  // namespace

double particle_steps_per_s(const Scene& scene) {
  return scene.frame_rate_hz * double(scene.particles->substeps);
}

double stable_time_step_s(double k, double c, double drag, int contacts) {
  // The positive root of z·k·dt² + (2z·c − 2γ)·dt − 4 = 0. Below it (2z·c − 2γ)·dt < 4, which is
  // the second condition, z·c·dt < 2 + γ·dt: the first implies it.
  const double z = contacts;
  const double a = z * k, b = 2.0 * z * c - 2.0 * drag;
  return (-b + std::sqrt(b * b + 16.0 * a)) / (2.0 * a);
}

double particle_step_limit_s(const ParticleParams& p) {
  return stable_time_step_s(p.stiffness_per_s2, p.damping_per_s, p.drag_per_s, kDesignContacts);
}

SettingsProblem particle_settings_problem(const Scene& scene) {
  const ParticleParams& p = *scene.particles;
  const double dt = 1.0 / particle_steps_per_s(scene);
  const double limit = particle_step_limit_s(p);
  if (dt >= limit) {
    int needed = int(std::floor(1.0 / (limit * scene.frame_rate_hz))) + 1;
    while (1.0 / (scene.frame_rate_hz * needed) >= limit) ++needed;  // the floor can land on the limit
    return {"particles.substeps", "a sub-step of " + number(dt * 1e3) + " ms is past the contact model's stability limit of " +
           number(limit * 1e3) + " ms (stiffness " + number(p.stiffness_per_s2) + "/s², damping " +
           number(p.damping_per_s) + "/s, drag " + number(p.drag_per_s) + "/s); use at least " +
           std::to_string(needed) + " sub-steps per frame, or a softer contact"};
  }
  if (p.diameter_mm >= scene.domain.width_mm || p.diameter_mm >= scene.domain.height_mm)
    return {"particles.diameter_mm", "particles of " + number(p.diameter_mm) + " mm do not fit in a " + number(scene.domain.width_mm) +
           " x " + number(scene.domain.height_mm) + " mm panel"};
  const double steps_per_s = particle_steps_per_s(scene);
  if (p.lifetime_s * steps_per_s > 2.0e9)
    return {"particles.lifetime_s", "a lifetime of " + number(p.lifetime_s) + " s is " + number(p.lifetime_s * steps_per_s) +
           " steps; at most 2e9 can be counted"};
  const double cells = double(cells_along(scene.domain.width_mm, cell_edge_mm(p))) *
                       double(cells_along(scene.domain.height_mm, cell_edge_mm(p)));
  if (cells >= 4.0e9)
    return {"particles.cell_mm", "the collision grid would have " + number(cells) + " cells; at most 4e9"};
  // The splat sums deposits as integers of bounded size: one particle's film under its centre must fit.
  const double splat_r = p.splat_radius_mm > 0.0 ? p.splat_radius_mm : p.diameter_mm;
  const double centre_mm = p.particle_volume_mm3 / (M_PI * splat_r * splat_r / 3.0);
  const double most_mm = double(kMaxDepositUnits) * double(kSplatUnitMm);
  if (centre_mm > most_mm)
    return {"particles.particle_volume_mm3", "a particle of " + number(p.particle_volume_mm3) + " mm³ over a splat radius of " +
                                                 number(splat_r) + " mm is " + number(centre_mm) +
                                                 " mm thick under its centre; the splat holds at most " +
                                                 number(most_mm) + " mm per particle"};
  return {};
}

ParticleLifetime particle_lifetime(const Scene& scene) {
  const ParticleParams& p = *scene.particles;
  const double steps_per_s = particle_steps_per_s(scene);
  const std::uint32_t steps = steps_in(p.lifetime_s, steps_per_s);
  return {steps, std::min(steps, steps_in(p.fade_s, steps_per_s))};
}

std::size_t particle_cell_count(const Scene& scene) {
  const double cell = cell_edge_mm(*scene.particles);
  return std::size_t(cells_along(scene.domain.width_mm, cell)) * std::size_t(cells_along(scene.domain.height_mm, cell));
}

ParticleModel make_particle_model(const Scene& scene) {
  const ParticleParams& p = *scene.particles;
  const double steps_per_s = particle_steps_per_s(scene);
  const double dt = 1.0 / steps_per_s;
  const double r = p.diameter_mm / 2.0;
  const double cell = cell_edge_mm(p);
  ParticleModel m{};
  m.radius_mm = float(r);
  m.diameter_mm = float(p.diameter_mm);
  m.diameter_sq = m.diameter_mm * m.diameter_mm;
  m.stiffness = float(p.stiffness_per_s2);
  m.damping = float(p.damping_per_s);
  m.gravity_x = float(p.gravity_x_mm_s2);
  m.gravity_y = float(p.gravity_y_mm_s2);
  m.dt_s = float(dt);
  m.drag_divisor = float(1.0 + p.drag_per_s * dt);
  m.max_speed = float(p.max_speed_mm_s);
  m.max_speed_sq = m.max_speed * m.max_speed;
  m.min_x = float(r);
  m.max_x = float(scene.domain.width_mm - r);
  m.min_y = float(r);
  m.max_y = float(scene.domain.height_mm - r);
  m.cell_mm = float(cell);
  m.cells_x = cells_along(scene.domain.width_mm, cell);
  m.cells_y = cells_along(scene.domain.height_mm, cell);
  m.max_per_cell = p.max_per_cell;
  m.key_bits = bits_for(std::uint32_t(m.cells_x) * std::uint32_t(m.cells_y));
  m.lifetime = particle_lifetime(scene);
  m.jitter_mm = float(p.jitter_mm);
  m.velocity_x = float(p.velocity_x_mm_s);
  m.velocity_y = float(p.velocity_y_mm_s);
  m.velocity_jitter = float(p.velocity_jitter_mm_s);
  m.seed = scene.seed;
  return m;
}

}  // namespace bleedsim
