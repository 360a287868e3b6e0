// The CPU reference of the particle step: loops over core/physics/particles.h. The sort is a counting
// sort, which is stable, so it orders (cell, slot) exactly as the GPU's radix sort does.
#include <algorithm>
#include <cstring>

#include "core/physics/particles.h"
#include "reference_cpu/parallel_rows.h"

namespace bleedsim {
namespace {

// Calls fn(slot) for every live slot in ascending slot order: the order a stable sort keeps ties in.
template <class Fn>
void for_live_slots_in_order(const ParticleArgs& a, const Fn& fn) {
  const int capacity = a.arrays.capacity, first = int(a.first_live_slot);
  const int wrapped = std::max(0, first + a.live_count - capacity);
  for (int slot = 0; slot < wrapped; ++slot) fn(slot);
  for (int slot = first; slot < first + a.live_count - wrapped; ++slot) fn(slot);
}

// Only the live slots are sorted: they come first in the GPU's sort of every slot too (empty
// slots carry the largest key), so sorted positions [0, live_count) agree between the backends.
// Aspirated particles in the live range carry that key too, and sort after the living.
void bin(const ParticleArgs& a) {
  const ParticleArrays& p = a.arrays;
  const ParticleModel& m = a.model;
  const std::uint32_t cells = cell_count(m), none = sentinel_key(m);
  // Count per cell, then each cell's start; cell_end serves as the write cursor and ends as the end.
  std::fill(p.cell_end, p.cell_end + cells, 0u);
  int living = 0;
  for_live_slots_in_order(a, [&](int slot) {
    p.cell_key[slot] = cell_key_of(p, m, slot);
    if (p.cell_key[slot] == none) return;
    ++p.cell_end[p.cell_key[slot]];
    ++living;
  });
  std::uint32_t at = 0;
  for (std::uint32_t c = 0; c < cells; ++c) {
    p.cell_start[c] = at;
    at += p.cell_end[c];
    p.cell_end[c] = p.cell_start[c];
  }
  for_live_slots_in_order(a, [&](int slot) {
    if (p.cell_key[slot] == none) return;
    const std::uint32_t to = p.cell_end[p.cell_key[slot]]++;
    p.sorted_key[to] = p.cell_key[slot];
    p.sorted_slot[to] = std::uint32_t(slot);
  });
  std::fill(p.sorted_key + living, p.sorted_key + a.live_count, none);
  for (int i = 0; i < living; ++i) gather_sorted(p, i);
}

}  // namespace

void cpu_twin(ParticlePhase phase, const ParticleArgs& a, int threads) {
  const int n = a.live_count;
  switch (phase) {
    case ParticlePhase::emit:
      for (int t = 0; t < a.new_count; ++t) emit_particle(a, t);
      break;
    case ParticlePhase::bin:
      bin(a);
      break;
    case ParticlePhase::collide:
      parallel_rows(n, threads_for_particles(n, threads), [&](int i) { collide_particle(a.arrays, a.model, i); });
      break;
    case ParticlePhase::integrate:
      parallel_rows(n, threads_for_particles(n, threads), [&](int t) { integrate_particle(a.arrays, a.model, live_slot(a, t)); });
      break;
  }
}

}  // namespace bleedsim
