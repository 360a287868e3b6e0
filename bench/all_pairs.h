#pragma once
// The baseline the collision grid is measured against: every live particle tested against every
// other (O(N²)), through the same add_pair() as the grid's collide, so only the neighbour loop
// differs. It visits the pairs in slot order, so its sums are not the grid's bits; the CPU and CUDA
// versions sum in the same order and agree with each other.
#include <cstddef>

#include "core/physics/particles.h"

namespace bleedsim {

// The contact acceleration of the particle in `slot` (written to acceleration[2·slot…]): the
// particles in slots 0, 1, …, capacity − 1 in turn, itself and empty slots left out.
BLEEDSIM_HD inline void all_pairs_accumulate(const ParticleModel& m, float px, float py, float vx, float vy,
                                             std::uint32_t age, std::uint32_t slot, float qx, float qy, float wx,
                                             float wy, std::uint32_t other_age, std::uint32_t other, PairSums* sums) {
  if (other == slot || !is_alive(m, other_age)) return;
  add_pair(m, px - qx, py - qy, vx, vy, pair_growth(m, age, other_age), slot, wx, wy, other, sums);
}

// Contact phase by all pairs, over host memory on `threads` threads.
void all_pairs_collide_cpu(const ParticleArrays& p, const ParticleModel& m, int threads);

#if BLEEDSIM_HAVE_CUDA
// The same over device memory: a tiled kernel, each block sharing one tile of particles at a time.
void all_pairs_collide_cuda(const ParticleArrays& p, const ParticleModel& m);
// A device-to-device copy (the benchmark's restore of the settled pile; Backend::upload is host to
// device only).
void copy_device_to_device_cuda(void* dst, const void* src, std::size_t bytes);
#endif

}  // namespace bleedsim
