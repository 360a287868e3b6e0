#include "core/effects/particles/particle_model.h"

#include <algorithm>
#include <cmath>

#include "core/effects/surface/surface_stage.h"
#include "core/runtime/count.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// At least one; a panel that holds more cells than 2^64 is uncountable, and refused.
Count cells_along(double panel_mm, double cell_mm) {
  return std::max(Count(1), Count::ceil_of(panel_mm / cell_mm));
}

// Only ever for a scene whose lifetime check passed: at most 2e9 steps.
std::uint32_t steps_in(double seconds, double steps_per_s) {
  return std::max(Count(1), Count::floor_of(std::round(seconds * steps_per_s))).to<std::uint32_t>();
}

// The deepest pile there can be: the panel's extent along gravity, or every slot of the ring heaped
// into a quarter-disc against a corner (hexagonally packed), whichever is less. Sticky blood heaps
// where it lands rather than levelling across the floor, and a quarter-disc is the deepest mound a
// pile leaning on two walls makes of its area.
double deepest_pile_mm(const ParticleParams& p, const Domain& d) {
  const double gx = std::abs(p.gravity_x_mm_s2), gy = std::abs(p.gravity_y_mm_s2), g = std::hypot(gx, gy);
  const double along = g > 0 ? (gx * d.width_mm + gy * d.height_mm) / g : d.height_mm;
  const double area_mm2 = double(p.capacity) * std::sqrt(3.0) / 2.0 * p.diameter_mm * p.diameter_mm;
  return std::min(along, 2.0 * std::sqrt(area_mm2 / M_PI));
}

// The deepest film there can be: the ring's whole volume pooled against the lowest wall, its
// surface sloping at g_t/g_n where gravity balances the pressure's gradient (g_n·∇h = g_t), over
// the panel's width across gravity: a wedge √(2·V·s / width) deep at the wall, or, past the wedge
// the panel's extent holds, that wedge with the rest spread evenly over it.
double deepest_film_mm(const ParticleParams& p, const Domain& d, double normal_mm_s2) {
  const double gx = std::abs(p.gravity_x_mm_s2), gy = std::abs(p.gravity_y_mm_s2), g = std::hypot(gx, gy);
  const double along = g > 0 ? (gx * d.width_mm + gy * d.height_mm) / g : d.height_mm;
  const double across = d.width_mm * d.height_mm / along, slope = g / normal_mm_s2;
  const double volume = double(p.capacity) * p.particle_volume_mm3;
  if (volume <= across * slope * along * along / 2.0) return std::sqrt(2.0 * volume * slope / across);
  return volume / (across * along) + slope * along / 2.0;
}

// The fewest sub-steps inside the limit, or kMaxSubsteps + 1 when more than kMaxSubsteps would be
// needed: a tiny particle's limit (or a vanishing one) asks for more steps than an int holds, so
// the count is checked before it is narrowed.
int fewest_stable_substeps(double frame_rate_hz, double limit_s) {
  const Count at_least = Count::floor_of(1.0 / (limit_s * frame_rate_hz));
  if (at_least > Count(kMaxSubsteps)) return kMaxSubsteps + 1;
  int n = std::max(1, at_least.to<int>());
  while (1.0 / (frame_rate_hz * n) >= limit_s) ++n;  // the floor can land on the limit
  return n;
}

// Surface mm per panel mm at least: 1 on the flat panel; on a mesh its least stretch, by which the
// panel's cells and margins grow so that they hold the surface's range and radius.
double least_stretch(const Scene& scene) {
  return scene.mesh ? panel_stretch(scene.mesh->mesh(), texture_panel(scene.domain)).least : 1.0;
}

// What the parameters make of the contact, the film and the time step on this panel at this frame
// rate: the resolution's one computation of them (resolve_particles, and the limits' checks of
// parameters not yet in a scene).
ParticleMechanics particle_mechanics(const ParticleParams& p, const Scene& scene) {
  const Domain& domain = scene.domain;
  const double frame_rate_hz = scene.frame_rate_hz;
  ParticleMechanics m{};
  const double d = p.diameter_mm, v = p.particle_volume_mm3;
  m.range_mm = d * (1.0 + p.cohesion_range);
  m.film_mm = v / (std::sqrt(3.0) / 2.0 * d * d);
  m.cohesion_mm_s2 = p.cohesion_mm3_s2 * d / v;
  m.pinning_mm_s2 = p.pinning_mm3_s2 * d / v;
  m.yield_mm_s2 = p.yield_mm2_s2 / m.film_mm;
  if (p.film_depth) {
    // No contact: the film's pressure pushes its parcels apart, and its fastest wave sets the step
    // (undamped but for the drag, which the step takes implicitly).
    const double normal = normal_gravity_mm_s2(p), kernel = kKernelSupport * d;
    m.kernel_mm = kernel;
    m.range_mm = std::max(m.range_mm, kernel);
    m.depth_mm = p.design_depth_mm > 0.0 ? p.design_depth_mm : deepest_film_mm(p, domain, normal);
    m.pressure_mm_s2 = normal * v * 140.0 / (M_PI * kernel * kernel * kernel);
    m.wave_per_s2 = kKernelWaveNumber * normal * m.depth_mm / (kernel * kernel);
    m.step_limit_s = stable_time_step_s(m.wave_per_s2, 0.0, p.drag_per_s, 1);
  } else {
    m.depth_mm = p.design_depth_mm > 0.0 ? p.design_depth_mm : deepest_pile_mm(p, domain);
    const double g = std::hypot(p.gravity_x_mm_s2, p.gravity_y_mm_s2);
    m.stiffness_per_s2 = (g * m.depth_mm + m.cohesion_mm_s2 * d) / (p.compression * d * d);
    m.damping_per_s = p.damping_ratio * std::sqrt(2.0 * m.stiffness_per_s2);
    m.step_limit_s = stable_time_step_s(m.stiffness_per_s2, m.damping_per_s, p.drag_per_s, kDesignContacts);
  }
  m.cell_mm = p.cell_mm > 0.0 ? p.cell_mm : m.range_mm;
  // A film with depth's fewest sub-steps also keep a particle at the speed limit under half a
  // diameter a step (step_within_a_radius), usually the shorter limit there; the contact's
  // stiffness is the shorter for the scenes it is made for, and a speed limit past it is refused.
  const double travel_limit_s = p.film_depth ? d / (2.0 * p.max_speed_mm_s) : m.step_limit_s;
  m.substeps = p.substeps > 0 ? p.substeps
                              : fewest_stable_substeps(frame_rate_hz, std::min(m.step_limit_s, travel_limit_s));
  m.dt_s = 1.0 / (frame_rate_hz * m.substeps);
  return m;
}

std::string number(double v) { return format_significant(v, 4); }

// What makes the step's stability limit what it is, for the messages: the contact's stiffness, or
// the film's fastest wave.
std::string what_limits_the_step(const ParticleParams& p, const ParticleMechanics& m) {
  if (p.film_depth)
    return "ω = " + number(std::sqrt(m.wave_per_s2)) + "/s on a " + number(m.depth_mm) + " mm film under " +
           number(normal_gravity_mm_s2(p)) + " mm/s² into the mucosa";
  return number(m.stiffness_per_s2) + "/s² for a " + number(m.depth_mm) + " mm pile at " + number(p.compression) +
         " compression";
}

// Cells of the collision grid over a width × height mm panel: the check refuses the grids too large
// to key before anything narrows the count.
Count particle_grid_cells(double cell_mm, double width_mm, double height_mm) {
  return cells_along(width_mm, cell_mm) * cells_along(height_mm, cell_mm);
}

// Steps in a particle's lifetime, before rounding (the check refuses more than can be counted).
double lifetime_steps(const ParticleParams& p, double frame_rate_hz, int substeps) {
  return p.lifetime_s * frame_rate_hz * double(substeps);
}

// The largest drop the mucosa holds against gravity (DropLimit).
DropLimit critical_drop(const ParticleParams& p, const ParticleMechanics& m) {
  const double pull = std::hypot(p.gravity_x_mm_s2, p.gravity_y_mm_s2) - m.yield_mm_s2;
  if (pull <= 0) return {true, 0, 0};
  const double radius = 2.0 * p.pinning_mm3_s2 / (m.film_mm * pull);
  return {false, radius, m.film_mm * M_PI * radius * radius};
}

}  // namespace

double normal_gravity_mm_s2(const ParticleParams& p) {
  if (p.gravity_normal_mm_s2 > 0.0) return p.gravity_normal_mm_s2;
  const double g = std::hypot(p.gravity_x_mm_s2, p.gravity_y_mm_s2);
  return g < kEarthGravityMmS2 ? std::sqrt(kEarthGravityMmS2 * kEarthGravityMmS2 - g * g) : 0.0;
}

ParamProblem cell_holds_the_range(const ParticleParams& p, const Scene& scene) {
  const double range = particle_mechanics(p, scene).range_mm;
  if (p.cell_mm == 0 || p.cell_mm >= range) return {};
  const std::string range_is =
      p.film_depth ? "the larger of diameter_mm × (1 + cohesion_range) and the film's kernel, " +
                         format_number(kKernelSupport) + " × diameter_mm,"
                   : "diameter_mm × (1 + cohesion_range)";
  return {"cell_mm", "must be 0 (the range) or at least the range, " + range_is + " = " + format_number(range) +
                         " mm (got " + format_number(p.cell_mm) + ")"};
}

LineGrid line_grid(const ParticleParams& p, const Domain& domain) {
  const auto steps_in_length = [&](double length_mm) {
    return std::max(1.0, std::round(length_mm / p.line_grid_mm));
  };
  const double steps_x = steps_in_length(domain.width_mm), steps_y = steps_in_length(domain.height_mm);
  const bool countable = (steps_x + 1.0) * (steps_y + 1.0) < double(kMaxGridCells);
  return {countable ? int(steps_x) : 0, countable ? int(steps_y) : 0, domain.width_mm / steps_x,
          domain.height_mm / steps_y};
}

ParamProblem line_grid_holds_a_parcel(const ParticleParams& p, const Scene& scene) {
  if (!p.film_depth) return {};
  const LineGrid grid = line_grid(p, scene.domain);
  const std::string panel =
      " on the " + format_number(scene.domain.width_mm) + " × " + format_number(scene.domain.height_mm) + " mm panel";
  if (grid.steps_x == 0)
    return {"line_grid_mm",
            "the contact line's grid would have more than 4e9 nodes" + panel + ": use a larger line_grid_mm"};
  const double finest = std::min(grid.step_x_mm, grid.step_y_mm);
  if (finest < p.diameter_mm)
    return {"line_grid_mm", "must be at least diameter_mm, " + format_number(p.diameter_mm) + " mm, once fitted to the panel" +
                                (finest < p.line_grid_mm ? " (" + format_number(finest) + " mm" + panel + ")" : "") +
                                ": finer, the film's own parcels leave dry nodes between them, and its inside has a "
                                "contact line (got " + format_number(p.line_grid_mm) + ")"};
  return {};
}

ParamProblem substep_inside_stability_limit(const ParticleParams& p, const Scene& scene) {
  const ParticleMechanics m = particle_mechanics(p, scene);
  if (m.dt_s < m.step_limit_s && m.substeps <= kMaxSubsteps) return {};
  ParticleParams fewest = p;
  fewest.substeps = 0;
  const int needed = particle_mechanics(fewest, scene).substeps;
  const std::string remedy = p.film_depth ? "a smaller design_depth_mm" : "more compression";
  const std::string what = p.film_depth ? "the film's waves" : "the contact";
  // No sub-step count the scene could give would do: the particles make the step too short.
  if (needed > kMaxSubsteps)
    return {"diameter_mm", "particles of " + number(p.diameter_mm) + " mm make " + what +
                               (p.film_depth ? " so fast (" : " so stiff (") + what_limits_the_step(p, m) +
                               ") that the stability limit of " + number(m.step_limit_s * 1e3) +
                               " ms needs more than " + std::to_string(kMaxSubsteps) +
                               " sub-steps per frame; use larger particles, or " + remedy};
  const std::string details = p.film_depth ? what_limits_the_step(p, m)
                                           : "stiffness " + what_limits_the_step(p, m) + ", damping " +
                                                 number(m.damping_per_s) + "/s";
  return {"substeps", "a sub-step of " + number(m.dt_s * 1e3) + " ms is past " +
                          (p.film_depth ? "the film's waves' " : "the contact's ") + "stability limit of " +
                          number(m.step_limit_s * 1e3) + " ms (" + details + ", drag " + number(p.drag_per_s) +
                          "/s); use at least " + std::to_string(needed) +
                          " sub-steps per frame (0 takes the fewest), larger particles, or " + remedy};
}

// A particle at the speed limit moves less than a radius a step, so none passes through another
// within the step (the contact sees every overlap while it is less than a diameter).
ParamProblem step_within_a_radius(const ParticleParams& p, const Scene& scene) {
  const double travel = p.max_speed_mm_s * particle_mechanics(p, scene).dt_s;
  if (travel < p.diameter_mm / 2) return {};
  return {"max_speed_mm_s", "moves " + number(travel) + " mm a sub-step, not less than half a diameter (" +
                                number(p.diameter_mm / 2) +
                                " mm): a particle could pass through another; lower "
                                "it or take more sub-steps"};
}

ParamProblem lifetime_countable(const ParticleParams& p, const Scene& scene) {
  const double steps = lifetime_steps(p, scene.frame_rate_hz, particle_mechanics(p, scene).substeps);
  if (steps <= 2.0e9) return {};
  return {"lifetime_s",
          "a lifetime of " + number(p.lifetime_s) + " s is " + number(steps) + " steps; at most 2e9 can be counted"};
}

// The grid's cells are keyed in 32 bits. Its cells come from cell_mm, or when that is 0 from the
// diameter (the range), so the refusal names whichever key set them.
ParamProblem grid_keyable(const ParticleParams& p, const Scene& scene) {
  const ParticleMechanics m = particle_mechanics(p, scene);
  const Domain& d = scene.domain;
  if (particle_grid_cells(m.cell_mm, d.width_mm, d.height_mm) < Count(kMaxGridCells)) return {};
  // For the message only: the count itself may be past what 64 bits hold.
  const double cells = std::ceil(d.width_mm / m.cell_mm) * std::ceil(d.height_mm / m.cell_mm);
  const std::string grid =
      "the collision grid would have " + number(cells) + " cells of " + number(m.cell_mm) + " mm; at most 4e9";
  if (p.cell_mm > 0) return {"cell_mm", grid};
  return {"diameter_mm", grid +
                             " (cells of the range, which the diameter sets): use larger particles, "
                             "or a larger cell_mm"};
}

double stable_time_step_s(double k, double c, double drag, int contacts) {
  // The positive root of z·k·dt² + (2z·c − 2γ)·dt − 4 = 0. Below it (2z·c − 2γ)·dt < 4, which is
  // the second condition, z·c·dt < 2 + γ·dt: the first implies it.
  const double z = contacts;
  const double a = z * k, b = 2.0 * z * c - 2.0 * drag;
  return (-b + std::sqrt(b * b + 16.0 * a)) / (2.0 * a);
}

ParticleSettings resolve_particles(const ParticleParams& p, const Scene& scene) {
  ParticleSettings settings{};
  const ParticleMechanics mech = particle_mechanics(p, scene);
  const double dt = mech.dt_s, stretch = least_stretch(scene);
  settings.mechanics = mech;
  settings.steps_per_s = scene.frame_rate_hz * double(mech.substeps);
  const std::uint32_t steps = steps_in(p.lifetime_s, settings.steps_per_s);
  settings.lifetime = {steps, std::min(steps, steps_in(p.fade_s, settings.steps_per_s))};
  settings.cells = particle_grid_cells(mech.cell_mm / stretch, scene.domain.width_mm, scene.domain.height_mm);
  settings.splat = make_splat_model(p, scene.domain);
  if (!p.film_depth) settings.drop = critical_drop(p, mech);

  const double r = p.diameter_mm / 2.0;
  // A disc touches a wall a radius from it; a parcel of a film with depth reaches the wall itself.
  const double margin =
      p.film_depth ? 0.0 : std::min(r / stretch, std::min(scene.domain.width_mm, scene.domain.height_mm) / 2.0);
  ParticleModel& m = settings.model;
  m.radius_mm = float(r);
  m.diameter_mm = float(p.diameter_mm);
  m.diameter_sq = m.diameter_mm * m.diameter_mm;
  m.range_mm = float(mech.range_mm);
  m.range_sq = m.range_mm * m.range_mm;
  m.band_inverse = mech.range_mm > p.diameter_mm ? float(1.0 / (mech.range_mm - p.diameter_mm)) : 0.0f;
  m.stiffness = float(mech.stiffness_per_s2);
  m.damping = float(mech.damping_per_s);
  m.pressure = float(mech.pressure_mm_s2);
  m.cohesion = float(mech.cohesion_mm_s2);
  if (p.film_depth) {
    // The grip as a stress and a line force (grip_from): the kernel's depth per parcel, the line's grid.
    const double kernel = mech.kernel_mm, v = p.particle_volume_mm3;
    m.kernel_inverse = float(1.0 / kernel);
    m.parcel_depth = float(7.0 * v / (M_PI * kernel * kernel));
    m.yield_stress = float(p.yield_mm2_s2);
    const LineGrid line = line_grid(p, scene.domain);
    m.line_grip = float(p.pinning_mm3_s2 / v);
    m.line_nodes_x = line.steps_x + 1;
    m.line_nodes_y = line.steps_y + 1;
    m.line_step_x = float(line.step_x_mm);
    m.line_step_y = float(line.step_y_mm);
    m.wetted_weight = float(kWettedDepthMm * line.step_x_mm * line.step_y_mm / v);
  } else {
    m.pinning = float(mech.pinning_mm_s2);
    m.yield = float(mech.yield_mm_s2);
  }
  m.edge_openness = kEdgeOpenness;
  m.edge_company = kEdgeCompany;
  m.birth_steps = float(steps_in(p.birth_s, 1.0 / dt));
  // New particles part at the speed a lone particle falls at: no faster than blood runs.
  m.birth_speed = float(std::hypot(p.gravity_x_mm_s2, p.gravity_y_mm_s2) / std::max(p.drag_per_s, 1.0));
  m.join_steps = float(steps_in(kFilmJoinS, 1.0 / dt));
  m.gravity_x = float(p.gravity_x_mm_s2);
  m.gravity_y = float(p.gravity_y_mm_s2);
  m.dt_s = float(dt);
  m.drag_divisor = float(1.0 + p.drag_per_s * dt);
  m.max_speed = float(p.max_speed_mm_s);
  m.max_speed_sq = m.max_speed * m.max_speed;
  const double rest_distance = p.rest_speed_mm_s * p.rest_s;
  m.rest_distance_sq = float(rest_distance * rest_distance);
  // At most the lifetime, whose steps are countable: a particle cannot rest longer than it lives.
  m.rest_steps = p.rest_s > 0.0 ? steps_in(std::min(p.rest_s, p.lifetime_s), 1.0 / dt) : 0u;
  const double wake_speed = kWakeSpeedFactor * p.rest_speed_mm_s;
  m.wake_speed_sq = float(wake_speed * wake_speed);
  m.min_x = float(margin);
  m.max_x = float(scene.domain.width_mm - margin);
  m.min_y = float(margin);
  m.max_y = float(scene.domain.height_mm - margin);
  // A wall bears a whole column of a pile where each of a bottom particle's two contacts bears 1/√3
  // of it: √3 the pair's stiffness makes the floor give as a bottom contact does, at most ⅔ of the
  // design compression on average under a pile of the design depth. A corner particle's two walls
  // and three contacts, 2√3 + 3 < kDesignContacts pairs' stiffness, keep it inside the stability
  // limit. Critically damped, 2√k_w, taken implicitly (so any damping is stable). A film with depth
  // has no contact: its walls mirror it (wall_images), and the spring is 0.
  const double wall_stiffness = std::sqrt(3.0) * mech.stiffness_per_s2;
  m.wall_stiffness = float(wall_stiffness);
  m.wall_damping_divisor = float(1.0 + 2.0 * std::sqrt(wall_stiffness) * dt);
  m.wall_give = float(margin / 2.0);
  const double cell_mm = mech.cell_mm / stretch;
  m.cell_mm = float(cell_mm);
  m.cells_x = cells_along(scene.domain.width_mm, cell_mm).to<int>();
  m.cells_y = cells_along(scene.domain.height_mm, cell_mm).to<int>();
  m.lifetime = settings.lifetime;
  m.jitter_mm = float(p.jitter_mm);
  m.velocity_x = float(p.velocity_x_mm_s);
  m.velocity_y = float(p.velocity_y_mm_s);
  m.velocity_jitter = float(p.velocity_jitter_mm_s);
  m.seed = scene.seed;
  return settings;
}

ParticleSettings resolve_particles(const Scene& scene) {
  return resolve_particles(scene.effects.get<ParticleParams>(), scene);
}

SplatModel make_splat_model(const ParticleParams& p, const Domain& domain) {
  const double r = p.splat_radius_mm > 0.0 ? p.splat_radius_mm : p.diameter_mm;
  const double pixel_area_mm2 = domain.width_mm / domain.width_px * (domain.height_mm / domain.height_px);
  SplatModel s{};
  s.radius_mm = float(r);
  s.radius_sq = float(r * r);
  s.units_per_mm3 = float(double(kSplatUnitsPerMm) / pixel_area_mm2);
  s.particle_volume_mm3 = float(p.particle_volume_mm3);
  return s;
}

Eigen::Vector3d device_gravity_mm_s2(const Scene& scene) {
  const ParticleParams* p = scene.effects.find<ParticleParams>();
  if (!p) return Eigen::Vector3d::Zero();
  return Eigen::Vector3d(p->gravity_x_mm_s2, -p->gravity_y_mm_s2, 0.0);
}

}  // namespace bleedsim
