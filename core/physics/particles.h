#pragma once
// Particle blood flow (report §2.2.2): blood leaves a wound as particles, each a parcel of the film
// of blood on the mucosa. Gravity pulls it along the panel, viscous drag against the tissue slows
// it, neighbours push back when they touch (a contact stiff enough that the deepest pile stays
// incompressible to a stated tolerance) and pull together within a short range (surface tension),
// and the mucosa grips it: the film's edge is pinned and all of it has a yield stress, so small
// drops stay where they are and a pool comes to rest. It piles up at the bottom, then fades.
//
// One step, in the order a backend runs it (docs/particles.md has the model and its limits):
//   emit       new particles at the bleeding cuts, into the ring buffer (oldest overwritten)
//   bin        each live particle's grid cell; a stable sort of (cell, slot); each cell's range; a film
//              with depth's depth at each particle and its contact line's grid (particle_line.h)
//   collide    contact and cohesion from every neighbour in the 3 × 3 cells around, in fixed order
//   integrate  gravity, contacts and drag (semi-implicit Euler), the mucosa's grip, panel bounds, age
// Once per frame the splat stage (core/physics/splat.h) turns the live particles into a film of blood.
//
// On a tissue mesh (core/physics/surface.h) the same model runs in surface millimetres: velocities,
// forces and gravity are the surface's, in each texel's frame, positions the panel's; a texel off the
// surface is a wall.
//
// Every update reads the old state and writes a new one (collide reads sorted copies, integrate
// touches only its own slot), sums run in a fixed order, and there are no float atomics: the CPU
// reference and the CUDA kernels give the same bits.
#include <cstddef>
#include <cstdint>

#include "core/physics/particle_bin.h"
#include "core/physics/particle_collide.h"
#include "core/physics/particle_emit.h"
#include "core/physics/particle_integrate.h"
#include "core/physics/particle_line.h"
#include "core/physics/particle_state.h"

namespace bleedsim {

// The twins: one phase of a step over host memory (CPU reference) or device memory (CUDA).
void cpu_twin(ParticlePhase phase, const ParticleArgs& args, int threads);
void cuda_twin(ParticlePhase phase, const ParticleArgs& args);
// Every phase of every step of a run, in order.
void cpu_twin(const ParticleSteps& steps, int threads);
void cuda_twin(const ParticleSteps& steps);
// Bytes of temporary storage the CUDA bin needs for `capacity` particles in `cells` cells.
std::size_t particle_sort_scratch_cuda(int capacity, std::uint32_t cells);

}  // namespace bleedsim
