#include "core/effects/particle_params.h"

#include <algorithm>
#include <cmath>

#include "core/effects/particle_model.h"
#include "core/physics/splat.h"
#include "core/runtime/message_text.h"
#include "core/runtime/scene.h"

namespace bleedsim {
namespace {

using P = ParticleParams;

std::string number(double v) { return format_significant(v, 4); }

// ---- what a file leaves out or says another way -----------------------------------------------

// The rate as a volume of blood: volume_mm3_per_s of particle_volume_mm3 particles. A fade not
// given is the default's, or the whole lifetime when that is shorter.
ParamProblem resolve_file(P& p, const Written& written, const Scene&) {
  if (written.numbers.count("volume_mm3_per_s")) {
    if (written.has("rate_per_s")) return {"volume_mm3_per_s", "give either rate_per_s or volume_mm3_per_s, not both"};
    // A particle's volume is the blood its splat spreads; with a volume rate it also sets the count.
    if (!written.has("particle_volume_mm3")) return {"volume_mm3_per_s", "needs particle_volume_mm3 beside it"};
    p.rate_per_s = written.numbers.at("volume_mm3_per_s") / p.particle_volume_mm3;
    if (!(p.rate_per_s <= kMaxParticleRate))
      return {"volume_mm3_per_s", "gives " + format_number(p.rate_per_s) + " particles per second; at most " +
                                      format_number(kMaxParticleRate)};
  }
  if (!written.has("fade_s")) p.fade_s = std::min(P{}.fade_s, p.lifetime_s);
  return {};
}

// ---- rules ------------------------------------------------------------------------------------

ParamProblem fade_within_lifetime(const P& p, const Scene&) {
  if (p.fade_s <= p.lifetime_s) return {};
  return {"fade_s", "must be at most lifetime_s, " + format_number(p.lifetime_s) + " s (got " +
                        format_number(p.fade_s) + ")"};
}

ParamProblem cell_holds_a_particle(const P& p, const Scene&) {
  if (p.cell_mm == 0 || p.cell_mm >= p.diameter_mm) return {};
  return {"cell_mm", "must be 0 (the diameter) or at least diameter_mm, " + format_number(p.diameter_mm) +
                         " mm (got " + format_number(p.cell_mm) + ")"};
}

ParamProblem substep_inside_stability_limit(const P& p, const Scene& scene) {
  const double dt = 1.0 / (scene.frame_rate_hz * p.substeps);
  const double limit = particle_step_limit_s(p);
  if (dt < limit) return {};
  int needed = int(std::floor(1.0 / (limit * scene.frame_rate_hz))) + 1;
  while (1.0 / (scene.frame_rate_hz * needed) >= limit) ++needed;  // the floor can land on the limit
  return {"substeps", "a sub-step of " + number(dt * 1e3) + " ms is past the contact model's stability limit of " +
                          number(limit * 1e3) + " ms (stiffness " + number(p.stiffness_per_s2) + "/s², damping " +
                          number(p.damping_per_s) + "/s, drag " + number(p.drag_per_s) + "/s); use at least " +
                          std::to_string(needed) + " sub-steps per frame, or a softer contact"};
}

ParamProblem particle_fits_the_panel(const P& p, const Scene& scene) {
  if (p.diameter_mm < scene.domain.width_mm && p.diameter_mm < scene.domain.height_mm) return {};
  return {"diameter_mm", "particles of " + number(p.diameter_mm) + " mm do not fit in a " +
                             number(scene.domain.width_mm) + " x " + number(scene.domain.height_mm) + " mm panel"};
}

ParamProblem lifetime_countable(const P& p, const Scene& scene) {
  const double steps = particle_lifetime_steps(p, scene.frame_rate_hz);
  if (steps <= 2.0e9) return {};
  return {"lifetime_s", "a lifetime of " + number(p.lifetime_s) + " s is " + number(steps) +
                            " steps; at most 2e9 can be counted"};
}

ParamProblem grid_keyable(const P& p, const Scene& scene) {
  const double cells = particle_grid_cells(p, scene.domain.width_mm, scene.domain.height_mm);
  if (cells < 4.0e9) return {};
  return {"cell_mm", "the collision grid would have " + number(cells) + " cells; at most 4e9"};
}

// The splat sums deposits as integers of bounded size: one particle's film under its centre must fit.
ParamProblem deposit_fits(const P& p, const Scene&) {
  const double splat_r = p.splat_radius_mm > 0.0 ? p.splat_radius_mm : p.diameter_mm;
  const double centre_mm = p.particle_volume_mm3 / (M_PI * splat_r * splat_r / 3.0);
  const double most_mm = double(kMaxDepositUnits) * double(kSplatUnitMm);
  if (centre_mm <= most_mm) return {};
  return {"particle_volume_mm3", "a particle of " + number(p.particle_volume_mm3) + " mm³ over a splat radius of " +
                                     number(splat_r) + " mm is " + number(centre_mm) +
                                     " mm thick under its centre; the splat holds at most " + number(most_mm) +
                                     " mm per particle"};
}

}  // namespace

const ParamTable<ParticleParams>& particle_table() {
  using T = ParamType;
  static const ParamTable<P> table{
      "particles",
      "declares the particle blood flow from the cuts, its model, and the defaults of cuts that give none",
      {{"capacity", T::integer, BLEEDSIM_MEMBER(P, capacity), "", {1, 268435456},
        "ring-buffer slots: the most particles alive at once; when it is full the oldest is overwritten"},
       {"diameter_mm", T::number, BLEEDSIM_MEMBER(P, diameter_mm), "mm", {0, 100, true},
        "particle size; less than the panel's width and height"},
       {"cell_mm", T::number, BLEEDSIM_MEMBER(P, cell_mm), "mm", {0, 1e4},
        "edge of the collision grid's cells: 0 (the diameter) or at least diameter_mm", "0: the diameter"},
       {"max_per_cell", T::integer, BLEEDSIM_MEMBER(P, max_per_cell), "", {1, 1024},
        "neighbours a particle visits per cell, at most"},
       {"rate_per_s", T::number, BLEEDSIM_MEMBER(P, rate_per_s), "1/s", {0, kMaxParticleRate},
        "particles per second from each bleeding cut (the cuts' default)"},
       {"volume_mm3_per_s", T::number, {}, "mm³/s", {0, 1e6},
        "the rate as a volume of blood: rate_per_s = volume_mm3_per_s / particle_volume_mm3; needs "
        "particle_volume_mm3, not with rate_per_s",
        "none"},
       {"particle_volume_mm3", T::number, BLEEDSIM_MEMBER(P, particle_volume_mm3), "mm³", {0, 1e6, true},
        "the blood one particle stands for: the volume its splat spreads into the film"},
       {"bleed_s", T::number, BLEEDSIM_MEMBER(P, bleed_s), "s", {0, 86400},
        "how long a cut bleeds particles after its start_s (the cuts' default)"},
       {"lifetime_s", T::number, BLEEDSIM_MEMBER(P, lifetime_s), "s", {0, 86400, true}, "how long a particle lives"},
       {"fade_s", T::number, BLEEDSIM_MEMBER(P, fade_s), "s", {0, 86400, true},
        "the end of the lifetime, over which a particle fades out; at most lifetime_s",
        "1, or lifetime_s when that is shorter"},
       {"gravity_mm_s2", T::vector, BLEEDSIM_VECTOR(P, gravity_x_mm_s2, gravity_y_mm_s2), "mm/s²", {-1e6, 1e6},
        "acceleration along the panel; y points down"},
       {"drag_per_s", T::number, BLEEDSIM_MEMBER(P, drag_per_s), "1/s", {0, 1e6},
        "viscous drag against the tissue: terminal speed is gravity / drag"},
       {"stiffness_per_s2", T::number, BLEEDSIM_MEMBER(P, stiffness_per_s2), "1/s²", {0, 1e12, true},
        "contact spring: push per mm of overlap"},
       {"damping_per_s", T::number, BLEEDSIM_MEMBER(P, damping_per_s), "1/s", {0, 1e6},
        "contact dashpot: resistance per mm/s of approach"},
       {"max_speed_mm_s", T::number, BLEEDSIM_MEMBER(P, max_speed_mm_s), "mm/s", {0, 1e5, true},
        "speed limit: no particle moves faster, so none passes through another"},
       {"substeps", T::integer, BLEEDSIM_MEMBER(P, substeps), "", {1, 100000},
        "physics steps per frame; inside the contact's stability limit"},
       {"jitter_mm", T::number, BLEEDSIM_MEMBER(P, jitter_mm), "mm", {0, 100},
        "a new particle is placed up to ± this from its cut, in x and in y"},
       {"velocity_mm_s", T::vector, BLEEDSIM_VECTOR(P, velocity_x_mm_s, velocity_y_mm_s), "mm/s", {-1e5, 1e5},
        "a new particle's velocity"},
       {"velocity_jitter_mm_s", T::number, BLEEDSIM_MEMBER(P, velocity_jitter_mm_s), "mm/s", {0, 1e5},
        "up to ± this added to a new particle's velocity, in x and in y"},
       {"splat_radius_mm", T::number, BLEEDSIM_MEMBER(P, splat_radius_mm), "mm", {0, 100},
        "how far from its centre a particle's blood spreads in the film: 0 (the diameter) or more",
        "0: the diameter"}},
      {{"fade_s is at most lifetime_s", fade_within_lifetime},
       {"cell_mm is 0 or at least diameter_mm", cell_holds_a_particle},
       {"a sub-step, 1 / (frame_rate_hz · substeps), is inside the contact's stability limit "
        "(docs/particles.md#the-stability-limit)",
        substep_inside_stability_limit},
       {"diameter_mm is less than the panel's width and height", particle_fits_the_panel},
       {"the lifetime is at most 2e9 steps", lifetime_countable},
       {"the collision grid has fewer than 4e9 cells", grid_keyable},
       {"one particle's film under its centre fits the splat's fixed-point sum", deposit_fits}},
      resolve_file};
  return table;
}

}  // namespace bleedsim
