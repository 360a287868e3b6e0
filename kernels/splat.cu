// The CUDA twin of the splat: a block per tile clears what the frame before left, a thread per slot
// deposits with integer atomics, and a block per tile converts the sum.
#include <cstddef>

#include "core/physics/splat.h"
#include "kernels/cuda_check.h"

namespace bleedsim {
namespace {

constexpr int kThreads = 256;
constexpr int kTilePixelsPerThread = kSplatTilePx * kSplatTilePx / kThreads;

// The pixel a tile's block gives its thread's n-th turn: rows of 32, so a warp's pixels are a row's.
struct TilePixel {
  int i, j;
  bool on_panel;
  std::size_t index;
};

__device__ TilePixel tile_pixel(const SplatArgs& a, int tile, int n) {
  const int k = threadIdx.x + n * kThreads;
  const int i = (tile % a.tiles.across) * kSplatTilePx + k % kSplatTilePx;
  const int j = (tile / a.tiles.across) * kSplatTilePx + k / kSplatTilePx;
  return {i, j, i < a.grid.width && j < a.grid.height, std::size_t(j) * a.grid.width + i};
}

// A tile the frame before did not stamp holds zeros already: its block leaves at once.
__global__ void clear_kernel(SplatArgs a) {
  const int tile = blockIdx.x;
  if (!stamped_before(a.tiles, tile)) return;
#pragma unroll
  for (int n = 0; n < kTilePixelsPerThread; ++n) {
    const TilePixel q = tile_pixel(a, tile, n);
    if (q.on_panel) a.units[q.index] = 0;
  }
}

// Integer atomics: the sum of the deposits does not depend on their order. A tile's stamp is
// written once a frame, by whichever thread finds it old (all write the same).
__global__ void deposit_kernel(SplatArgs a) {
  const int slot = blockIdx.x * blockDim.x + threadIdx.x;
  if (slot >= a.capacity) return;
  auto* units = reinterpret_cast<unsigned long long*>(a.units);
  splat_particle(
      a, slot,
      [&](std::size_t pixel, std::uint64_t amount) { atomicAdd(units + pixel, static_cast<unsigned long long>(amount)); },
      [&](int tile) {
        if (!stamped_now(a.tiles, tile)) a.tiles.stamp[tile] = a.tiles.now;
      });
}

// Each thread reads its pixels' sums before it writes any film, so its reads are in flight together.
__global__ void film_kernel(SplatArgs a) {
  const int tile = blockIdx.x;
  const bool reached = stamped_now(a.tiles, tile);
  float film[kTilePixelsPerThread];
#pragma unroll
  for (int n = 0; n < kTilePixelsPerThread; ++n) {
    const TilePixel q = tile_pixel(a, tile, n);
    if (q.on_panel) film[n] = film_mm(a, q.index, reached);
  }
#pragma unroll
  for (int n = 0; n < kTilePixelsPerThread; ++n) {
    const TilePixel q = tile_pixel(a, tile, n);
    if (q.on_panel) a.thickness_mm[q.index] = film[n];
  }
}

}  // namespace

void cuda_twin(const SplatArgs& a) {
  const unsigned tiles = unsigned(splat_tile_count(a.grid));
  clear_kernel<<<tiles, kThreads>>>(a);
  check_launch("clear_kernel");
  deposit_kernel<<<(a.capacity + kThreads - 1) / kThreads, kThreads>>>(a);
  check_launch("deposit_kernel");
  film_kernel<<<tiles, kThreads>>>(a);
  check_launch("film_kernel");
}

}  // namespace bleedsim
