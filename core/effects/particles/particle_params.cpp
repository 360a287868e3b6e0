#include "core/effects/particles/particle_params.h"

#include <algorithm>
#include <cmath>

#include "core/effects/particles/particle_model.h"
#include "core/physics/splat.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

using P = ParticleParams;

std::string number(double v) { return format_significant(v, 4); }

// ---- what a file leaves out -------------------------------------------------------------------

// A fade not given is the default's, or the whole lifetime when that is shorter. A film with depth
// has no cohesion unless the file gives one (which a rule then refuses), and its births end by
// distance, birth_s only bounding them (kLongestFilmBirthS).
ParamProblem resolve_file(P& p, const Written& written, const Scene&) {
  if (!written.has("fade_s")) p.fade_s = std::min(P{}.fade_s, p.lifetime_s);
  if (p.film_depth && !written.has("cohesion_mm3_s2")) p.cohesion_mm3_s2 = 0.0;
  if (p.film_depth && !written.has("birth_s")) p.birth_s = kLongestFilmBirthS;
  return {};
}

// ---- rules ------------------------------------------------------------------------------------

ParamProblem fade_within_lifetime(const P& p, const Scene&) {
  if (p.fade_s <= p.lifetime_s) return {};
  return {"fade_s", "must be at most lifetime_s, " + format_number(p.lifetime_s) + " s (got " +
                        format_number(p.fade_s) + ")"};
}

// The contact's stiffness comes from the load it must bear: gravity over the pile, or cohesion. (A
// film with depth has its pressure instead: normal_gravity_present.)
ParamProblem something_to_bear(const P& p, const Scene&) {
  if (p.film_depth || std::hypot(p.gravity_x_mm_s2, p.gravity_y_mm_s2) > 0 || p.cohesion_mm3_s2 > 0) return {};
  return {"gravity_mm_s2", "with no gravity and no cohesion the contact has no load to be made stiff for; "
                           "give either"};
}

// A new particle's speed is at most |velocity| + √2·velocity_jitter: within the speed limit, or the
// limit would cut its emission short and say nothing.
ParamProblem emitted_within_the_limit(const P& p, const Scene&) {
  const double fastest = std::hypot(p.velocity_x_mm_s, p.velocity_y_mm_s) + std::sqrt(2.0) * p.velocity_jitter_mm_s;
  if (fastest <= p.max_speed_mm_s) return {};
  return {"velocity_mm_s", "a new particle may leave at up to " + number(fastest) +
                               " mm/s (|velocity_mm_s| + √2 × velocity_jitter_mm_s), past max_speed_mm_s = " +
                               number(p.max_speed_mm_s)};
}

// A film with depth is pushed apart by its weight into the mucosa: with none (a vertical panel, or
// an in-plane gravity as strong as Earth's) nothing would, and surface tension, which would, is not
// modelled for it yet.
ParamProblem normal_gravity_present(const P& p, const Scene&) {
  if (!p.film_depth || normal_gravity_mm_s2(p) > 0) return {};
  return {"gravity_normal_mm_s2", "a film with depth needs gravity into the mucosa, and with gravity_mm_s2 = [" +
                                      number(p.gravity_x_mm_s2) + ", " + number(p.gravity_y_mm_s2) +
                                      "] Earth's leaves none; give it, or set film_depth = false"};
}

// Cohesion pulls touching discs together; between parcels of a film with depth, which overlap as
// deep as the film is, a pull would be a pressure against its own, and its surface tension is not
// modelled yet.
ParamProblem no_cohesion_in_depth(const P& p, const Scene&) {
  if (!p.film_depth || p.cohesion_mm3_s2 == 0) return {};
  return {"cohesion_mm3_s2", "a film with depth has no cohesion between its parcels (got " +
                                 number(p.cohesion_mm3_s2) + "); leave it out, or 0"};
}

ParamProblem particle_fits_the_panel(const P& p, const Scene& scene) {
  if (p.diameter_mm < scene.domain.width_mm && p.diameter_mm < scene.domain.height_mm) return {};
  return {"diameter_mm", "particles of " + number(p.diameter_mm) + " mm do not fit in a " +
                             number(scene.domain.width_mm) + " x " + number(scene.domain.height_mm) + " mm panel"};
}

// The splat sums deposits as integers of bounded size: a particle's whole blood in one pixel (a
// splat that reaches no pixel centre) must fit.
ParamProblem deposit_fits(const P& p, const Scene& scene) {
  const Domain& d = scene.domain;
  const double pixel_mm2 = d.width_mm / d.width_px * (d.height_mm / d.height_px);
  const double whole_mm = p.particle_volume_mm3 / pixel_mm2;
  const double most_mm = double(kMaxDepositUnits) * double(kSplatUnitMm);
  if (whole_mm <= most_mm) return {};
  return {"particle_volume_mm3", "a particle of " + number(p.particle_volume_mm3) + " mm³ in one pixel of " +
                                     number(pixel_mm2) + " mm² is " + number(whole_mm) +
                                     " mm thick; the splat holds at most " + number(most_mm) +
                                     " mm per particle in a pixel"};
}

}  // namespace

const ParamTable<ParticleParams>& particle_table() {
  using T = ParamType;
  static const std::string birth_doc =
      "over this a new particle's overlaps are undone by moving it, at no more than gravity / drag, not by pushing "
      "it: a burst parts without a blast (with film_depth: the longest a birth lasts, " +
      number(kLongestFilmBirthS) + " s unless given; it ends once no other birth is nearer than " +
      number(kBirthsApart) + " of a diameter)";
  static const ParamTable<P> table{
      "particles",
      "declares the particle blood flow from the cuts, its model, and the wound's defaults for cuts that give none",
      {{"capacity", T::integer, BLEEDSIM_MEMBER(P, capacity), "", {1, 268435456},
        "ring-buffer slots: the most particles alive at once; when it is full the oldest is overwritten"},
       {"diameter_mm", T::number, BLEEDSIM_MEMBER(P, diameter_mm), "mm", {0, 100, true},
        "particle size; less than the panel's width and height"},
       {"particle_volume_mm3", T::number, BLEEDSIM_MEMBER(P, particle_volume_mm3), "mm³", {0, 1e6, true},
        "the blood one particle stands for: the volume its splat spreads into the film"},
       {"cell_mm", T::number, BLEEDSIM_MEMBER(P, cell_mm), "mm", {0, 1e4},
        "edge of the collision grid's cells: 0 (the range) or at least diameter_mm × (1 + cohesion_range)",
        "0: the range"},
       {"flow_mm3_per_s_per_mm", T::number, BLEEDSIM_MEMBER(P, flow_mm3_per_s_per_mm), "mm³/s/mm", {0, 1e6},
        "blood per second per mm of wound as a cut starts (the cuts' default)"},
       {"bleed_s", T::number, BLEEDSIM_MEMBER(P, bleed_s), "s", {0, 86400},
        "how long a cut bleeds after its start_s (the cuts' default)"},
       {"clot_s", T::number, BLEEDSIM_MEMBER(P, clot_s), "s", {0, 86400},
        "a cut's flow falls as exp(−t / clot_s) as it clots; 0: it does not (the cuts' default)"},
       {"lifetime_s", T::number, BLEEDSIM_MEMBER(P, lifetime_s), "s", {0, 86400, true}, "how long a particle lives"},
       {"fade_s", T::number, BLEEDSIM_MEMBER(P, fade_s), "s", {0, 86400, true},
        "the end of the lifetime, over which a particle fades out; at most lifetime_s",
        "1, or lifetime_s when that is shorter"},
       {"gravity_mm_s2", T::vector, BLEEDSIM_VECTOR(P, gravity_x_mm_s2, gravity_y_mm_s2), "mm/s²", {-1e6, 1e6},
        "acceleration along the panel; y points down"},
       {"drag_per_s", T::number, BLEEDSIM_MEMBER(P, drag_per_s), "1/s", {0, 1e6},
        "viscous drag against the tissue: a lone particle slides at gravity / drag"},
       {"film_depth", T::flag, BLEEDSIM_MEMBER(P, film_depth), "", {},
        "the film has depth: its hydrostatic pressure under gravity_normal_mm_s2 spreads it and pools deepen "
        "(shallow water), instead of touching particles one layer thick; not on a tissue mesh"},
       {"gravity_normal_mm_s2", T::number, BLEEDSIM_MEMBER(P, gravity_normal_mm_s2), "mm/s²", {0, 1e6},
        "with film_depth, gravity into the mucosa: the film's hydrostatic pressure",
        "0: what Earth's 9810 mm/s² leaves after gravity_mm_s2, √(9810² − |g|²)"},
       {"compression", T::number, BLEEDSIM_MEMBER(P, compression), "", {0, 0.5, true},
        "the deepest pile's overlap, as a fraction of the diameter: sets the contact's stiffness"},
       {"design_depth_mm", T::number, BLEEDSIM_MEMBER(P, design_depth_mm), "mm", {0, 1e4},
        "the deepest pile the contact is made stiff for; with film_depth, the deepest film the step is made "
        "stable for", "0: the panel's extent along gravity, or the ring's whole capacity heaped into a quarter-disc "
        "in a corner, whichever is less; with film_depth, the ring's whole volume pooled against the lowest wall"},
       {"damping_ratio", T::number, BLEEDSIM_MEMBER(P, damping_ratio), "", {0, 1},
        "the contact's dashpot, as a fraction of a pair's critical damping"},
       {"cohesion_mm3_s2", T::number, BLEEDSIM_MEMBER(P, cohesion_mm3_s2), "mm³/s²", {0, 1e6},
        "surface tension: the pull between neighbours, a force per unit length of the film's edge per unit "
        "density; none with film_depth", "20, or 0 with film_depth"},
       {"cohesion_range", T::number, BLEEDSIM_MEMBER(P, cohesion_range), "diameters", {0, 2},
        "how far beyond contact cohesion reaches"},
       {"pinning_mm3_s2", T::number, BLEEDSIM_MEMBER(P, pinning_mm3_s2), "mm³/s²", {0, 1e6},
        "the mucosa's grip on the film's edge (contact-angle hysteresis), per unit length per unit density"},
       {"line_grid_mm", T::number, BLEEDSIM_MEMBER(P, line_grid_mm), "mm", {0, 1e3, true},
        "with film_depth, how far apart the nodes are that the film's edge is found on (fitted to the panel): its "
        "contact line, which the pinning holds, is measured at this scale whatever the particles"},
       {"yield_mm2_s2", T::number, BLEEDSIM_MEMBER(P, yield_mm2_s2), "mm²/s²", {0, 1e6},
        "blood's yield stress per unit density: the grip on every particle"},
       {"birth_s", T::number, BLEEDSIM_MEMBER(P, birth_s), "s", {0, 10},
        birth_doc.c_str()},
       {"max_speed_mm_s", T::number, BLEEDSIM_MEMBER(P, max_speed_mm_s), "mm/s", {0, 1e5, true},
        "speed limit: no particle moves faster; with the sub-step, less than half a diameter a step"},
       {"rest_speed_mm_s", T::number, BLEEDSIM_MEMBER(P, rest_speed_mm_s), "mm/s", {0, 1e5},
        "blood that moves less than this × rest_s in rest_s has stopped and sleeps, until a neighbour moves "
        "at twice this (or the tip, a new particle or a force past twice its grip disturbs it)"},
       {"rest_s", T::number, BLEEDSIM_MEMBER(P, rest_s), "s", {0, 86400},
        "how long blood stays within rest_speed_mm_s × rest_s of one spot before it sleeps; blood never sleeps "
        "when this is 0 or at least lifetime_s"},
       {"substeps", T::integer, BLEEDSIM_MEMBER(P, substeps), "", {0, double(kMaxSubsteps)},
        "physics steps per frame, inside the contact's stability limit (with film_depth, the film's waves')",
        "0: the fewest inside the limit (with film_depth, and under half a diameter a step at max_speed_mm_s)"},
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
       {"cell_mm is 0 or at least the range, diameter_mm × (1 + cohesion_range) (with film_depth, at least the kernel, "
        "2.6 × diameter_mm)",
        cell_holds_the_range},
       {"gravity or cohesion is not zero: the contact's stiffness comes from the load it bears", something_to_bear},
       {"diameter_mm is less than the panel's width and height", particle_fits_the_panel},
       {"with film_depth, gravity into the mucosa is more than 0", normal_gravity_present},
       {"with film_depth, cohesion_mm3_s2 is 0", no_cohesion_in_depth},
       {"the collision grid has fewer than 4e9 cells", grid_keyable},
       {"a sub-step, 1 / (frame_rate_hz · substeps), is inside the stability limit of the contact, or with "
        "film_depth of the film's waves (docs/particles.md#the-stability-limit), in at most 100000 sub-steps",
        substep_inside_stability_limit},
       {"the lifetime is at most 2e9 steps", lifetime_countable},
       {"max_speed_mm_s × the sub-step is less than half a diameter", step_within_a_radius},
       {"with film_depth, line_grid_mm is at least the diameter, and its grid has fewer than 4e9 nodes", line_grid_holds_a_parcel},
       {"a new particle's fastest speed, |velocity_mm_s| + √2 × velocity_jitter_mm_s, is within max_speed_mm_s",
        emitted_within_the_limit},
       {"one particle's whole blood in a single pixel fits the splat's fixed-point sum", deposit_fits}},
      resolve_file};
  return table;
}

}  // namespace bleedsim
