// The all-pairs baseline over host memory (bench/all_pairs.h).
#include "bench/all_pairs.h"

#include "reference_cpu/parallel_rows.h"

namespace bleedsim {

void all_pairs_collide_cpu(const ParticleArrays& p, const ParticleModel& m, int threads) {
  parallel_rows(p.capacity, threads, [&](int i) {
    if (!is_alive(m, p.age[i])) return;
    const float px = p.position[2 * i], py = p.position[2 * i + 1];
    const float vx = p.velocity[2 * i], vy = p.velocity[2 * i + 1];
    PairSums sums;
    for (int j = 0; j < p.capacity; ++j)
      all_pairs_accumulate(m, px, py, vx, vy, p.age[i], std::uint32_t(i), p.position[2 * j], p.position[2 * j + 1],
                           p.velocity[2 * j], p.velocity[2 * j + 1], p.age[j], std::uint32_t(j), &sums);
    finish_pair_sums(p, m, std::uint32_t(i), sums);
  });
}

}  // namespace bleedsim
