// The CPU twin of the splat: the deposits of bands of slots summed on the threads, each into the
// pixel's 64-bit integer by an atomic add (integer sums: neither the order nor the thread count
// changes a bit), then the sum converted row by row, leaving it zero (and the film downsampled, the
// blur's own pass).
#include <algorithm>

#include "core/physics/pixel_kernels.h"
#include "core/physics/splat.h"
#include "reference_cpu/parallel_rows.h"

namespace bleedsim {
namespace {

// Calls fn(first pixel, end pixel, tile) for each tile's stretch of row j.
template <class Fn>
void for_each_tile_of_row(const SplatArgs& a, int j, const Fn& fn) {
  const std::size_t row = std::size_t(j) * a.grid.width;
  for (int i0 = 0; i0 < a.grid.width; i0 += kSplatTilePx)
    fn(row + i0, row + std::min(i0 + kSplatTilePx, a.grid.width), splat_tile(a.tiles, i0, j));
}

}  // namespace

void cpu_twin(const SplatArgs& a, int threads) {
  const int bands = threads_for_particles(a.capacity, threads);
  if (bands == 1) {
    for (int slot = 0; slot < a.capacity; ++slot)
      splat_particle(
          a, slot, [&](std::size_t pixel, std::uint64_t units) { a.units[pixel] += units; },
          [&](int tile) { a.tiles.stamp[tile] = a.tiles.now; });
  } else {
    // Threads stamping one tile store the same value; atomically, as C++ asks of any shared store.
    parallel_rows(a.capacity, bands, [&](int slot) {
      splat_particle(
          a, slot,
          [&](std::size_t pixel, std::uint64_t units) { __atomic_fetch_add(&a.units[pixel], units, __ATOMIC_RELAXED); },
          [&](int tile) { __atomic_store_n(&a.tiles.stamp[tile], a.tiles.now, __ATOMIC_RELAXED); });
    });
  }
  parallel_rows(a.grid.height, threads, [&](int j) {
    for_each_tile_of_row(a, j, [&](std::size_t first, std::size_t end, int tile) {
      if (film_in_place(a, tile)) return;
      const bool reached = stamped_now(a.tiles, tile);
      for (std::size_t p = first; p < end; ++p) a.thickness_mm[p] = film_mm(a, p, reached);
      if (reached) std::fill(a.units + first, a.units + end, std::uint64_t(0));
    });
  });
  if (a.downsample.low) cpu_twin(BlurDownsample{a.downsample}, threads);
}

}  // namespace bleedsim
