#pragma once
// The particle blood flow's parameters (report §2.2.2; docs/particles.md). Units: mm, s, and
// accelerations per unit mass.
#include "core/runtime/params.h"

namespace bleedsim {

// The most particles a cut may emit per second: keeps one step's count well inside 32 bits.
constexpr double kMaxParticleRate = 1.0e8;

// Present in a Scene only when the scene calls for the particles.
struct ParticleParams {
  int capacity = 65536;            // ring-buffer slots
  double diameter_mm = 0.2;
  double cell_mm = 0.0;            // grid cell edge; 0: the diameter
  int max_per_cell = 8;            // neighbours visited per cell, at most
  double rate_per_s = 500.0;       // default particles per second per bleeding cut
  double bleed_s = 2.0;            // default bleeding time of a cut
  double lifetime_s = 30.0;
  double fade_s = 1.0;             // the last part of the lifetime, over which a particle fades
  double gravity_x_mm_s2 = 0.0;    // along the panel; y points down
  double gravity_y_mm_s2 = 1000.0;
  double drag_per_s = 100.0;       // viscous drag: sticky, slow blood
  double stiffness_per_s2 = 4.0e5; // contact spring, per mm of overlap
  double damping_per_s = 100.0;    // contact dashpot, per mm/s of approach speed
  double max_speed_mm_s = 100.0;   // no particle moves faster: none passes through another
  int substeps = 40;               // physics steps per frame
  double jitter_mm = 0.05;         // emission position jitter, ±
  double velocity_x_mm_s = 0.0;    // emission velocity
  double velocity_y_mm_s = 0.0;
  double velocity_jitter_mm_s = 5.0;
  double particle_volume_mm3 = 0.004;  // the blood one particle stands for (the splat's film)
  double splat_radius_mm = 0.0;        // the film's footprint; 0: the diameter
};

const ParamTable<ParticleParams>& particle_table();

}  // namespace bleedsim
