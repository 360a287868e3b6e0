#pragma once
// Emission (core/physics/particles.h): each step's new particles at the bleeding cuts, into the
// ring buffer, the oldest overwritten.
#include <cstddef>
#include <cstdint>

#include "core/physics/counter_hash.h"
#include "core/physics/particle_state.h"
#include "core/physics/surface.h"

namespace bleedsim {

// A jittered position past a bound is mirrored back inside it, not clamped onto it: clamping would
// stack a cut's particles on the wall line, where contacts with each other point along the wall
// and nothing can push them off it.
BLEEDSIM_HD inline float reflect_inside(float v, float low, float high) {
  if (v < low) v = low + (low - v);
  if (v > high) v = high - (v - high);
  return clamp_float(v, low, high);
}

// The emitter of new particle t: the last whose first_new is at most t. A binary search: a stroke
// makes a cut a millimetre, and a thread that walked them in turn waited on a load for each.
BLEEDSIM_HD inline const Emitter& emitter_of(const ParticleArgs& a, std::uint32_t t) {
  int low = 0, high = a.emitter_count - 1;  // emitters[0].first_new is 0
  while (low < high) {
    const int middle = low + (high - low + 1) / 2;
    if (a.emitters[middle].first_new <= t) low = middle;
    else high = middle - 1;
  }
  return a.emitters[low];
}

// New particle t of this step: at its cut, jittered by the counter hash of (seed, id, step). A film
// with depth's parcels are placed over the jitter's square by the R2 sequence instead: births that
// land within a diameter of each other must part before they join (particle_integrate.h's
// step_birth), and independent draws put some that close at any rate, so that at small sizes,
// several births a step, they crowded at the wound; consecutive R2 points keep apart.
BLEEDSIM_HD inline void emit_particle(const ParticleArgs& a, int t) {
  const ParticleModel& m = a.model;
  const Emitter& from = emitter_of(a, std::uint32_t(t));
  const std::uint64_t id = from.first_id + (std::uint32_t(t) - from.first_new);
  const std::size_t slot = std::size_t(id % std::uint64_t(a.arrays.capacity));
  // A new particle takes the slot of the live one before it, overwriting it: counted here when that
  // one was aspirated, as the accounting has counted it overwritten (the live range is this step's,
  // before emission).
  if (in_live_range(a.first_live_slot, a.live_count, a.arrays.capacity, slot) && is_aspirated(a.arrays.age[slot]))
    count_one(&a.arrays.fates->overwritten);
  const auto jitter = [&](std::uint32_t stream) {
    return signed_unit(counter_hash(m.seed, id, a.step, stream));
  };
  const auto place = [&](std::uint32_t axis) {
    return has_depth(m) ? signed_unit(even_point(m.seed, id, axis)) : jitter(axis);
  };
  float jx = m.jitter_mm * place(0), jy = m.jitter_mm * place(1);
  // On a mesh the jitter is on the surface; one that lands off it falls back to the cut.
  if (curved(m.surface)) to_panel(frame_at(m.surface, from.x_mm, from.y_mm), jx, jy, &jx, &jy);
  float x = reflect_inside(from.x_mm + jx, m.min_x, m.max_x), y = reflect_inside(from.y_mm + jy, m.min_y, m.max_y);
  if (curved(m.surface) && !on_surface(m.surface, x, y)) {
    x = clamp_float(from.x_mm, m.min_x, m.max_x);
    y = clamp_float(from.y_mm, m.min_y, m.max_y);
  }
  set_pair(a.arrays.position, slot, {x, y});
  set_pair(a.arrays.velocity, slot,
           {m.velocity_x * from.speed_scale + m.velocity_jitter * jitter(2),
            m.velocity_y * from.speed_scale + m.velocity_jitter * jitter(3)});
  a.arrays.age[slot] = 0;
  a.arrays.rest[slot] = has_depth(m) ? kBeingBorn : 0u;
  set_pair(a.arrays.anchor, slot, {x, y});
}

// Which of this step's new particles a slot receives (new_count: none). Their ids run on from the
// first emitter's first_id, so new particle e goes to slot (first id + e) mod capacity: a backend
// may emit each new particle from the thread that owns its slot.
BLEEDSIM_HD inline int new_particle_in(const ParticleArgs& a, std::size_t slot) {
  if (a.new_count == 0) return 0;
  const std::uint64_t capacity = std::uint64_t(a.arrays.capacity);
  const std::uint64_t e = (std::uint64_t(slot) + capacity - a.emitters[0].first_id % capacity) % capacity;
  return e < std::uint64_t(a.new_count) ? int(e) : a.new_count;
}

}  // namespace bleedsim
