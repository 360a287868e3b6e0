// The CPU twin of the splat: the deposits summed by one thread, in slot order (integer sums, so the
// order does not matter), then the per-pixel conversion.
#include <algorithm>

#include "core/physics/pixel_kernels.h"
#include "core/physics/splat.h"

namespace bleedsim {

void cpu_twin(const SplatArgs& a, int threads) {
  const std::size_t pixels = std::size_t(a.grid.width) * std::size_t(a.grid.height);
  std::fill(a.units, a.units + pixels, std::uint64_t(0));
  for (int slot = 0; slot < a.capacity; ++slot)
    splat_particle(a, slot, [&](std::size_t pixel, std::uint64_t units) { a.units[pixel] += units; });
  cpu_twin(splat_thickness(a), threads);
}

}  // namespace bleedsim
