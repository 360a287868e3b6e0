#include <algorithm>

#include "core/physics/splat.h"
#include "reference_cpu/parallel_rows.h"

namespace bleedsim {

void cpu_twin(const SplatArgs& a, int threads) {
  const std::size_t pixels = std::size_t(a.grid.width) * std::size_t(a.grid.height);
  std::fill(a.units, a.units + pixels, std::uint64_t(0));
  for (int slot = 0; slot < a.capacity; ++slot)
    splat_particle(a, slot, [&](std::size_t pixel, std::uint64_t units) { a.units[pixel] += units; });
  parallel_rows(a.grid.height, threads, [&](int j) {
    for (int i = 0; i < a.grid.width; ++i) {
      const std::size_t p = std::size_t(j) * a.grid.width + i;
      a.thickness_mm[p] = thickness_from_units(a.units[p]);
    }
  });
}

}  // namespace bleedsim
