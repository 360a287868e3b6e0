#pragma once
// The ring buffer's scratch arrays in one allocation, and the empty ring's initial contents: shared
// by the particle stage and the benchmarks, so both run exactly the arrays a scene runs.
#include <cstddef>

#include "core/physics/particles.h"
#include "core/runtime/backend.h"

namespace bleedsim {

// Bytes of every ParticleArrays member that is not state (position, velocity, age, rest, anchor), for
// `capacity` particles on a grid of `cells` cells (cell_count() of the model), a contact line's grid
// of `line_nodes` nodes (line_node_count()) and `sort_scratch_bytes` of sort storage.
std::size_t particle_scratch_bytes(std::size_t cells, std::size_t line_nodes, int capacity,
                                   std::size_t sort_scratch_bytes);
// Points those members into `base`, which holds particle_scratch_bytes() bytes.
void point_particle_scratch(ParticleArrays& arrays, std::size_t cells, std::size_t line_nodes, void* base,
                            std::size_t sort_scratch_bytes);
// An empty ring: every slot at the origin, at rest and never used; no particle aspirated.
// Every byte that is hashed starts defined.
void clear_particles(Backend& backend, const ParticleArrays& arrays);

}  // namespace bleedsim
