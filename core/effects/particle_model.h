#pragma once
// The particle model's constants for a run, made on the host from the scene, and the limits a
// scene must respect for the model to stay stable (docs/particles.md derives them).
#include <string>

#include "core/effects/particle_params.h"
#include "core/physics/particles.h"
#include "core/runtime/scene.h"

namespace bleedsim {

// Physics steps per second: frame rate × sub-steps.
double particle_steps_per_s(const Scene& scene);
// Steps in a particle's lifetime, before rounding (a scene's check refuses more than can be counted).
double particle_lifetime_steps(const ParticleParams& params, double frame_rate_hz);

// The largest stable sub-step when particles touch up to `contacts` others. In a hexagonal pile
// (six contacts) the fastest mode has ω² = 6k and damping 6c; with z contacts, ω² ≈ zk. Semi-
// implicit Euler with implicit drag γ keeps it bounded while z·k·dt² + (2z·c − 2γ)·dt < 4 (which
// implies the other Jury condition, z·c·dt < 2 + γ·dt).
double stable_time_step_s(double stiffness_per_s2, double damping_per_s, double drag_per_s, int contacts);

// The contacts the enforced limit allows for: six in a hexagonal pile, and a margin for the seven
// or eight that particles reach where a pile is overloaded or crowds against a wall.
constexpr int kDesignContacts = 8;

// The sub-step limit a scene must keep to (kDesignContacts).
double particle_step_limit_s(const ParticleParams& params);

// Cells of the collision grid over a width × height mm panel, as a double: a scene's check
// (particle_table()) refuses the grids too large to key before anything counts them in integers.
double particle_grid_cells(const ParticleParams& params, double width_mm, double height_mm);

// The rest require scene.particles.
ParticleModel make_particle_model(const Scene& scene);
// Parts of the model, for what needs no more of it: the lifetime (the splat's), and the number of
// cells of the collision grid (cell_count() of the model; the memory estimate's).
ParticleLifetime particle_lifetime(const Scene& scene);
std::size_t particle_cell_count(const Scene& scene);

}  // namespace bleedsim
