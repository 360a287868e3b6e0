#include "core/effects/particle_model.h"

#include <algorithm>
#include <cmath>

namespace bleedsim {
namespace {

double cell_edge_mm(const ParticleParams& p) { return p.cell_mm > 0.0 ? p.cell_mm : p.diameter_mm; }

// As a double: a grid too large to count in integers is measured before it is refused.
double cells_along(double panel_mm, double cell_mm) { return std::max(1.0, std::ceil(panel_mm / cell_mm)); }

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

double particle_lifetime_steps(const ParticleParams& p, double frame_rate_hz) {
  return p.lifetime_s * frame_rate_hz * double(p.substeps);
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

double particle_grid_cells(const ParticleParams& p, double width_mm, double height_mm) {
  return cells_along(width_mm, cell_edge_mm(p)) * cells_along(height_mm, cell_edge_mm(p));
}

ParticleLifetime particle_lifetime(const Scene& scene) {
  const ParticleParams& p = *scene.particles;
  const double steps_per_s = particle_steps_per_s(scene);
  const std::uint32_t steps = steps_in(p.lifetime_s, steps_per_s);
  return {steps, std::min(steps, steps_in(p.fade_s, steps_per_s))};
}

std::size_t particle_cell_count(const Scene& scene) {
  return std::size_t(particle_grid_cells(*scene.particles, scene.domain.width_mm, scene.domain.height_mm));
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
  m.cells_x = int(cells_along(scene.domain.width_mm, cell));
  m.cells_y = int(cells_along(scene.domain.height_mm, cell));
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
