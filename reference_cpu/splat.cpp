// The CPU twin of the splat: the deposits of bands of slots summed on the threads, each into the
// pixel's 64-bit integer by an atomic add (integer sums: neither the order nor the thread count
// changes a bit), then the per-pixel conversion.
#include <algorithm>

#include "core/physics/pixel_kernels.h"
#include "core/physics/splat.h"
#include "reference_cpu/parallel_rows.h"

namespace bleedsim {

void cpu_twin(const SplatArgs& a, int threads) {
  const int width = a.grid.width;
  parallel_rows(a.grid.height, threads, [&](int j) {
    std::fill(a.units + std::size_t(j) * width, a.units + std::size_t(j + 1) * width, std::uint64_t(0));
  });
  const int bands = threads_for_particles(a.capacity, threads);
  if (bands == 1) {
    for (int slot = 0; slot < a.capacity; ++slot)
      splat_particle(a, slot, [&](std::size_t pixel, std::uint64_t units) { a.units[pixel] += units; });
  } else {
    parallel_rows(a.capacity, bands, [&](int slot) {
      splat_particle(a, slot, [&](std::size_t pixel, std::uint64_t units) {
        __atomic_fetch_add(&a.units[pixel], units, __ATOMIC_RELAXED);
      });
    });
  }
  cpu_twin(splat_thickness(a), threads);
}

}  // namespace bleedsim
