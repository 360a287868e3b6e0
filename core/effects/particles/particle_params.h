#pragma once
// The particle blood flow's parameters (report §2.2.2; docs/particles.md has the model). Units:
// mm, s, and accelerations per unit mass.
#include "core/runtime/params.h"

namespace bleedsim {

template <class P>
struct Effect;

// The most particles a cut may emit per second: keeps one step's count well inside 32 bits.
constexpr double kMaxParticleRate = 1.0e8;

// The longest a film with depth's birth lasts unless the scene says (docs/particles.md#births-of-a-
// film-with-depth). Births end by distance; this bounds the ones that cannot part soon. 1,200
// parcels born at one point part by distance in 1.2 s; 12,000 do not part by 3 s, and join over
// kFilmJoinS then, spreading within issue 36's bounds (fastest 15 mm/s, against 2·g/γ = 20).
constexpr double kLongestFilmBirthS = 3.0;
// A birth that is still crowded when birth_s runs out joins the film over this (kJoining,
// core/physics/particle_state.h): long against the time a film one layer deep takes to level a
// bump a kernel wide, γR²/(g_n·h) = 0.02 s at the shipped size (less at every smaller one).
constexpr double kFilmJoinS = 0.25;

// Present in a Scene only when the scene calls for the particles.
struct ParticleParams {
  int capacity = 16384;              // ring-buffer slots
  double diameter_mm = 0.2;
  double particle_volume_mm3 = 0.004;  // the blood one particle stands for (the film it makes)
  double cell_mm = 0.0;              // grid cell edge; 0: the interaction range
  // The wound: blood per second per mm of wound, for how long, and how fast it clots (the cuts'
  // defaults; a cut says how many mm of wound it stands for).
  double flow_mm3_per_s_per_mm = 2.0;
  double bleed_s = 2.0;
  double clot_s = 0.0;               // the flow falls as exp(−t/clot_s); 0: it does not
  double lifetime_s = 30.0;
  double fade_s = 1.0;               // the last part of the lifetime, over which a particle fades
  double gravity_x_mm_s2 = 0.0;      // along the panel; y points down
  double gravity_y_mm_s2 = 1000.0;
  double drag_per_s = 100.0;         // viscous drag against the tissue
  // The film with depth (docs/particles.md#a-film-with-depth): the particles are parcels of a
  // shallow film whose depth is their kernel-summed volume, pushed apart by its hydrostatic
  // pressure under gravity into the mucosa, instead of touching discs one layer thick.
  bool film_depth = false;
  double gravity_normal_mm_s2 = 0.0;  // into the mucosa; 0: what Earth's gravity leaves after gravity_mm_s2
  // The contact: stiff enough that the deepest pile compresses by at most `compression` of a
  // diameter (docs/particles.md derives the stiffness), damped at `damping_ratio` of critical.
  double compression = 0.02;
  double design_depth_mm = 0.0;      // the deepest pile; 0: what the panel and the capacity allow
  double damping_ratio = 0.1;
  // Surface tension and the mucosa's grip. Cohesion and pinning are forces per unit length of the
  // film's edge per unit density (mm³/s²): cohesion pulls neighbours within cohesion_range
  // diameters beyond contact together; pinning holds the film's edge where it stands
  // (contact-angle hysteresis). Yield holds every particle (blood's yield stress per unit density,
  // mm²/s²). Pinning and yield are static friction: each holds up to its strength.
  double cohesion_mm3_s2 = 20.0;
  double cohesion_range = 0.3;
  double pinning_mm3_s2 = 30.0;
  // With film_depth, how far apart the nodes are that its contact line (the pinning's length) is
  // measured on: fixed in mm, so that the line is the same whatever the particles
  // (core/physics/particle_line.h); the shipped kernel's support.
  double line_grid_mm = 0.52;
  double yield_mm2_s2 = 50.0;         // the film's yield stress per unit density (mm²/s²)
  double birth_s = 0.1;              // a new particle is shifted out of overlaps, not pushed, over this
                                     // (film_depth: at most this, kLongestFilmBirthS unless given)
  double max_speed_mm_s = 100.0;     // no particle moves faster
  // Rest: blood that moves less than rest_speed_mm_s × rest_s in rest_s has stopped, and sleeps until
  // a neighbour moves at twice that speed, or the tip, a new particle or a force past twice its grip
  // disturbs it (docs/particles.md#rest). rest_s = 0: it never sleeps.
  double rest_speed_mm_s = 0.2;
  double rest_s = 0.25;
  int substeps = 0;                  // physics steps per frame; 0: the fewest the contact allows
  double jitter_mm = 0.05;           // emission position jitter, ±
  double velocity_x_mm_s = 0.0;      // emission velocity
  double velocity_y_mm_s = 0.0;
  double velocity_jitter_mm_s = 5.0;
  double splat_radius_mm = 0.0;      // the film's footprint; 0: the diameter
};

const ParamTable<ParticleParams>& particle_table();
// Its row: the particles' and the splat's stages (particle_stage.cpp).
const Effect<ParticleParams>& particle_effect();

}  // namespace bleedsim
