#pragma once
// The bin (core/physics/particles.h): each live particle's grid cell, and its sorted copy for
// collide.
#include <cstddef>
#include <cstdint>

#include "core/physics/hd.h"
#include "core/physics/particle_state.h"

namespace bleedsim {

BLEEDSIM_HD inline std::uint32_t cell_count(const ParticleModel& m) {
  return std::uint32_t(m.cells_x) * std::uint32_t(m.cells_y);
}

// One past the last cell.
BLEEDSIM_HD inline std::uint32_t sentinel_key(const ParticleModel& m) { return cell_count(m); }

// Clamped before the conversion: float→int of out-of-range values differs between CPU and GPU.
BLEEDSIM_HD inline int cell_coordinate(float v_mm, float cell_mm, int cells) {
  return static_cast<int>(clamp_float(floorf(v_mm / cell_mm), 0.0f, static_cast<float>(cells - 1)));
}

BLEEDSIM_HD inline std::uint32_t cell_key_of(const ParticleArrays& p, const ParticleModel& m, int slot) {
  if (!is_alive(m, p.age[slot])) return sentinel_key(m);
  const FloatPair at = pair_at(p.position, std::size_t(slot));
  const int cx = cell_coordinate(at.x, m.cell_mm, m.cells_x);
  const int cy = cell_coordinate(at.y, m.cell_mm, m.cells_y);
  return std::uint32_t(cy) * std::uint32_t(m.cells_x) + std::uint32_t(cx);
}

// The sorted positions [begin, end) of the particles in cells x0 … x1 of row y: the cells of a row
// are consecutive keys, so their particles are one run of the sorted order.
struct SortedRun {
  std::uint32_t begin, end;
};
BLEEDSIM_HD inline SortedRun row_run(const ParticleArrays& p, const ParticleModel& m, int y, int x0, int x1) {
  const std::uint32_t row = std::uint32_t(y) * std::uint32_t(m.cells_x);
  return {p.cell_start[row + std::uint32_t(x0)], p.cell_start[row + std::uint32_t(x1) + 1]};
}

// The n-th live slot in ascending slot order, n < live_count (the live range wraps round the ring):
// the order the bin takes them in, and so the order it keeps within a cell.
BLEEDSIM_HD inline int nth_live_slot_ascending(const ParticleArgs& a, int n) {
  const int past_end = int(a.first_live_slot) + a.live_count - a.arrays.capacity;
  const int wrapped = past_end > 0 ? past_end : 0;
  return n < wrapped ? n : int(a.first_live_slot) + (n - wrapped);
}

// The sorted copies collide reads, so no thread reads a slot another thread is writing.
BLEEDSIM_HD inline void gather_sorted(const ParticleArrays& p, const ParticleModel& m, int i) {
  const std::uint32_t slot = p.sorted_slot[i];
  set_pair(p.sorted_position, std::size_t(i), pair_at(p.position, slot));
  set_pair(p.sorted_velocity, std::size_t(i), pair_at(p.velocity, slot));
  p.sorted_birth[i] = has_depth(m) ? p.rest[slot] : p.age[slot];
}

}  // namespace bleedsim
