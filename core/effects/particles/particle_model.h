#pragma once
// The particle model resolved for a scene: its constants, derived on the host from the parameters
// and the scene (docs/particles.md derives each), once per scene (ParticleSettings, which Resolved
// holds and every consumer reads); and the limits a scene must respect for the model to be stable
// and to mean what it says (rules of particle_table()).
#include <cstddef>

#include "core/effects/particles/particle_params.h"
#include "core/physics/particles.h"
#include "core/physics/splat.h"
#include "core/runtime/count.h"
#include "core/scene/scene.h"

namespace bleedsim {

// The contacts the stability limit allows for: six in a hexagonal pile, and a margin for the seven
// or eight that particles reach where a pile is overloaded or crowds against a wall.
constexpr int kDesignContacts = 8;
// A sleeper wakes when a neighbour moves faster than this many times the rest speed: above the
// creep that put it to sleep, so that two creeping neighbours do not keep waking each other.
constexpr double kWakeSpeedFactor = 2.0;

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

// Earth's gravity, mm/s²: what gravity_normal_mm_s2 = 0 takes the normal part from.
constexpr double kEarthGravityMmS2 = 9810.0;
// A film with depth (docs/particles.md#a-film-with-depth) sums its depth with a 2D Wendland C2
// kernel reaching this many diameters: 2·1.3 particle spacings of a one-layer film, the support
// that kernel is commonly used at (Dehnen & Aly 2012) ...
constexpr double kKernelSupport = 2.6;
// ... whose pressure's fastest wave has ω² = g_n·h·max_k k²·Ŵ(k) = g_n·h·κ/R², κ = 10.18 (Ŵ the
// kernel's Fourier transform, R its support; the maximum is at k·R = 5.16, computed once by
// quadrature).
constexpr double kKernelWaveNumber = 10.18;

// A node of the contact line's grid (line_grid_mm) is wet, its colour 1, once the film there is this
// deep (mm); thinner, its colour is its depth over this. Far below the yield's depth (0.05 mm under
// the default's gravity), where films stop, so that every film that runs is wholly wet inside; a lone
// parcel at the shipped size (0.004 mm³ over a 0.52 mm square: 0.015 mm) colours its nodes 0.37 (at a
// square's centre) to 1 (on a node): a drop, with its own line.
constexpr double kWettedDepthMm = 0.01;

// Gravity into the mucosa: gravity_normal_mm_s2, or when that is 0 what Earth's leaves after the
// panel's own, √(9810² − |g|²) (0 when |g| is Earth's or more).
double normal_gravity_mm_s2(const ParticleParams& params);

// What the parameters make of the contact, the film and the time step, in double.
struct ParticleMechanics {
  double range_mm;          // d·(1 + cohesion_range), or the kernel's support when the film has depth: the
                            // farthest a neighbour acts from
  double kernel_mm;         // R = kKernelSupport·d: the film's kernel (0: the film has no depth)
  double pressure_mm_s2;    // g_n·V·140/(π·R³): a neighbour's push is this·q·(1 − q)³, q = r/R
  double cell_mm;           // the grid's cell edge: cell_mm, or the range
  double film_mm;           // t = V / (√3/2·d²): the film a hexagonal layer of particles makes
  double depth_mm;          // H: the deepest pile the contact is made stiff enough for (the film with depth:
                            // the deepest film its step is made stable for)
  double cohesion_mm_s2;    // a neighbour's pull: q_c·d / V (a force per unit length of edge, per particle)
  double pinning_mm_s2;     // the edge's grip: q_p·d / V
  double yield_mm_s2;       // every particle's grip: (τ_y/ρ) / t
  double stiffness_per_s2;  // k = (|g|·H + a_coh·d) / (ε·d²): the deepest pile's overlap is ε·d (0: the
                            // film has depth, and no contact)
  double wave_per_s2;       // the film with depth: its fastest wave's ω² = κ·g_n·H / R² (0: none)
  double damping_per_s;     // c = ζ·√(2k): ζ of a pair's critical damping
  double step_limit_s;      // the largest stable sub-step, for kDesignContacts contacts
  int substeps;             // the scene's, or the fewest inside the limit (kMaxSubsteps + 1: more than allowed)
  double dt_s;              // 1 / (frame rate × substeps)
};

// The largest drop the mucosa holds against gravity: a round patch of the film (thickness t,
// radius R) whose edge the pinning grips (q_p per unit length, per unit density) and whose every
// particle the yield grips (a_y) is held while t·πR²·(|g| − a_y) ≤ 2πR·q_p, so up to
// R_c = 2·q_p / (t·(|g| − a_y)) and V_c = t·π·R_c². None when the yield alone holds everything.
struct DropLimit {
  bool holds_any;  // the yield is at least gravity: no drop slides
  double radius_mm;
  double volume_mm3;
};

// The largest stable sub-step when particles touch up to `contacts` others. In a hexagonal pile
// (six contacts) the fastest mode has ω² = 6k and damping 6c; with z contacts, ω² ≈ zk. Semi-
// implicit Euler with implicit drag γ keeps it bounded while z·k·dt² + (2z·c − 2γ)·dt < 4 (which
// implies the other Jury condition, z·c·dt < 2 + γ·dt).
double stable_time_step_s(double stiffness_per_s2, double damping_per_s, double drag_per_s, int contacts);

// The particle model of a scene, resolved once (Resolved holds it; resolve_particles() makes it).
struct ParticleSettings {
  ParticleMechanics mechanics;  // the contact, the film, the sub-step
  double steps_per_s;           // physics steps per second: frame rate × sub-steps
  ParticleLifetime lifetime;    // in steps: the particles' and the splat's
  Count cells;                  // of the collision grid (cell_count() of the model; the memory estimate's)
  ParticleModel model;          // the constants both backends read (its surface map the stage's to set)
  SplatModel splat;             // the film's footprint (make_splat_model)
  DropLimit drop;               // the largest drop the mucosa holds (the contact's; none for a film with depth)
};
// `params` on this scene's panel, frame rate and tissue mesh (a scene's own: scene.effects'). Only
// for parameters that particle_table() accepts.
ParticleSettings resolve_particles(const ParticleParams& params, const Scene& scene);
ParticleSettings resolve_particles(const Scene& scene);

// The splat's constants: a particle's blood spread over splat_radius_mm (0: the diameter).
SplatModel make_splat_model(const ParticleParams& params, const Domain& domain);

// Gravity in the device frame (mm/s²), for a tissue mesh: the particles' gravity_mm_s2 means the
// same on a mesh as on the flat panel, which faces the user: x right, y down the panel (the
// device's −y). Zero without particles.
Eigen::Vector3d device_gravity_mm_s2(const Scene& scene);

// A film with depth's contact line is measured on a grid of nodes (core/physics/particle_line.h):
// line_grid_mm apart, fitted to the panel so that nodes lie on its walls. Steps 0: more nodes than
// a grid may have.
struct LineGrid {
  int steps_x, steps_y;        // the grid's squares along the panel's width and height
  double step_x_mm, step_y_mm;
};
LineGrid line_grid(const ParticleParams& params, const Domain& domain);

// The limits, rules of particle_table() that depend on the model's constants.
ParamProblem cell_holds_the_range(const ParticleParams& params, const Scene& scene);
ParamProblem grid_keyable(const ParticleParams& params, const Scene& scene);
ParamProblem substep_inside_stability_limit(const ParticleParams& params, const Scene& scene);
ParamProblem lifetime_countable(const ParticleParams& params, const Scene& scene);
ParamProblem step_within_a_radius(const ParticleParams& params, const Scene& scene);
ParamProblem line_grid_holds_a_parcel(const ParticleParams& params, const Scene& scene);

}  // namespace bleedsim
