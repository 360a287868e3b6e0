#pragma once
// The particle model's constants for a run, derived on the host from the parameters and the scene
// (docs/particles.md derives each), and the limits a scene must respect for the model to be
// stable and to mean what it says.
#include <cstddef>

#include "core/effects/particles/particle_params.h"
#include "core/physics/particles.h"
#include "core/runtime/count.h"
#include "core/scene/scene.h"

namespace bleedsim {

// The contacts the stability limit allows for: six in a hexagonal pile, and a margin for the seven
// or eight that particles reach where a pile is overloaded or crowds against a wall.
constexpr int kDesignContacts = 8;

// The most sub-steps a frame may take ([particles].substeps, and the fewest the limit asks for).
constexpr int kMaxSubsteps = 100000;
// The most cells the collision grid may have: its keys are 32-bit.
constexpr std::uint64_t kMaxGridCells = 4'000'000'000;

// A particle is on the film's edge when the directions to its neighbours (weighted as the cohesion)
// sum to more than this: inside a layer they cancel, on a straight edge of a hexagonal layer they
// sum to √3, at a corner or a lone particle's more.
constexpr float kEdgeOpenness = 1.0f;
// ... and so is one with fewer neighbours than this (weighted as the cohesion): a drop of a few.
constexpr float kEdgeCompany = 2.5f;

// What the parameters make of the contact, the film and the time step, in double.
struct ParticleMechanics {
  double range_mm;          // d·(1 + cohesion_range): the farthest a neighbour acts from
  double cell_mm;           // the grid's cell edge: cell_mm, or the range
  double film_mm;           // t = V / (√3/2·d²): the film a hexagonal layer of particles makes
  double depth_mm;          // H: the deepest pile the contact is made stiff enough for
  double cohesion_mm_s2;    // a neighbour's pull: q_c·d / V (a force per unit length of edge, per particle)
  double pinning_mm_s2;     // the edge's grip: q_p·d / V
  double yield_mm_s2;       // every particle's grip: (τ_y/ρ) / t
  double stiffness_per_s2;  // k = (|g|·H + a_coh·d) / (ε·d²): the deepest pile's overlap is ε·d
  double damping_per_s;     // c = ζ·√(2k): ζ of a pair's critical damping
  double step_limit_s;      // the largest stable sub-step, for kDesignContacts contacts
  int substeps;             // the scene's, or the fewest inside the limit (kMaxSubsteps + 1: more than allowed)
  double dt_s;              // 1 / (frame rate × substeps)
};
ParticleMechanics particle_mechanics(const ParticleParams& params, const Domain& domain, double frame_rate_hz);

// The largest drop the mucosa holds against gravity: a round patch of the film (thickness t,
// radius R) whose edge the pinning grips (q_p per unit length, per unit density) and whose every
// particle the yield grips (a_y) is held while t·πR²·(|g| − a_y) ≤ 2πR·q_p, so up to
// R_c = 2·q_p / (t·(|g| − a_y)) and V_c = t·π·R_c². None when the yield alone holds everything.
struct DropLimit {
  bool holds_any;  // the yield is at least gravity: no drop slides
  double radius_mm;
  double volume_mm3;
};
DropLimit critical_drop(const ParticleParams& params, const Domain& domain, double frame_rate_hz);

// The largest stable sub-step when particles touch up to `contacts` others. In a hexagonal pile
// (six contacts) the fastest mode has ω² = 6k and damping 6c; with z contacts, ω² ≈ zk. Semi-
// implicit Euler with implicit drag γ keeps it bounded while z·k·dt² + (2z·c − 2γ)·dt < 4 (which
// implies the other Jury condition, z·c·dt < 2 + γ·dt).
double stable_time_step_s(double stiffness_per_s2, double damping_per_s, double drag_per_s, int contacts);

// Steps in a particle's lifetime, before rounding (a scene's check refuses more than can be counted).
double particle_lifetime_steps(const ParticleParams& params, double frame_rate_hz, int substeps);

// Cells of the collision grid over a width × height mm panel: a scene's check (particle_table())
// refuses the grids too large to key before anything narrows the count.
Count particle_grid_cells(double cell_mm, double width_mm, double height_mm);

// The rest require scene.particles.
ParticleModel make_particle_model(const Scene& scene);
// Physics steps per second: frame rate × sub-steps.
double particle_steps_per_s(const Scene& scene);
// Parts of the model, for what needs no more of it: the lifetime (the splat's), and the number of
// cells of the collision grid (cell_count() of the model; the memory estimate's).
ParticleLifetime particle_lifetime(const Scene& scene);
Count particle_cell_count(const Scene& scene);

}  // namespace bleedsim
