// The CUDA twin of the splat: a thread per slot deposits with integer atomics, and a block per tile
// converts the sum (and downsamples the film).
#include <cstddef>
#include <iterator>
#include <stdexcept>
#include <utility>

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

// The tile's first column and row, in units of `scale` pixels (1: the panel's; the factor: the
// downsampled image's).
__device__ int2 tile_origin(const SplatArgs& a, int tile, int scale = 1) {
  return {(tile % a.tiles.across) * (kSplatTilePx / scale), (tile / a.tiles.across) * (kSplatTilePx / scale)};
}

__device__ TilePixel tile_pixel(const SplatArgs& a, int tile, int n) {
  const int k = threadIdx.x + n * kThreads;
  const int2 origin = tile_origin(a, tile);
  const int i = origin.x + k % kSplatTilePx, j = origin.y + k / kSplatTilePx;
  return {i, j, i < a.grid.width && j < a.grid.height, std::size_t(j) * a.grid.width + i};
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

// Each thread reads its pixels' sums before it writes any film (or sets a sum back to zero), so its
// reads are in flight together.
// With a downsample factor (one of kBlurFactors; 0: none), the block keeps its tile's film and
// takes the means of the blocks in it (a tile's side is a multiple of every factor: no block
// crosses a tile's edge); the factor is the kernel's constant, so a block's loops unroll.
constexpr bool tiles_hold_whole_blocks() {
  for (const int f : kBlurFactors)
    if (kSplatTilePx % f != 0) return false;
  return true;
}
static_assert(tiles_hold_whole_blocks(), "a blur block would cross a splat tile's edge");

template <int Factor>
__global__ void film_kernel(SplatArgs a) {
  const int tile = blockIdx.x;
  if (film_is_zero(a, tile)) {  // the whole block leaves here together
    if (!film_in_place(a, tile))
#pragma unroll
      for (int n = 0; n < kTilePixelsPerThread; ++n) {
        const TilePixel q = tile_pixel(a, tile, n);
        if (q.on_panel) a.thickness_mm[q.index] = 0.0f;
      }
    // The blur's vertical pass writes `low` too: its means are written every frame, here zeros.
    if constexpr (Factor > 0) {
      const BlurArgs& b = a.downsample;
      constexpr int side = kSplatTilePx / Factor;
      const int2 origin = tile_origin(a, tile, Factor);
      for (int k = threadIdx.x; k < side * side; k += kThreads) {
        const int i = origin.x + k % side, j = origin.y + k / side;
        if (i < b.low_width && j < b.low_height) b.low[std::size_t(j) * b.low_width + i] = 0.0f;
      }
    }
    return;
  }
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
    if (!q.on_panel) continue;
    a.thickness_mm[q.index] = film[n];
    if (reached) a.units[q.index] = 0;
  }
  if constexpr (Factor > 0) {
    __shared__ float kept[kSplatTilePx][kSplatTilePx + 1];  // + 1: a column's reads fall in different banks
#pragma unroll
    for (int n = 0; n < kTilePixelsPerThread; ++n) {
      const int k = threadIdx.x + n * kThreads;
      if (tile_pixel(a, tile, n).on_panel) kept[k / kSplatTilePx][k % kSplatTilePx] = film[n];
    }
    __syncthreads();
    BlurArgs b = a.downsample;
    b.factor = Factor;
    constexpr int side = kSplatTilePx / Factor;  // the tile's blocks a row
    const int2 origin = tile_origin(a, tile), low_origin = tile_origin(a, tile, Factor);
#pragma unroll
    for (int k = threadIdx.x; k < side * side; k += kThreads) {
      const int i = low_origin.x + k % side, j = low_origin.y + k / side;
      if (i < b.low_width && j < b.low_height)
        b.low[std::size_t(j) * b.low_width + i] =
            block_mean_of(b, i, j, [&](int x, int y) { return kept[y - origin.y][x - origin.x]; });
    }
  }
}

// The film's kernel for the blur's factor: one instantiation for each of kBlurFactors. False when
// the factor is none of them.
template <std::size_t... I>
bool launch_film_downsampled(const SplatArgs& a, unsigned tiles, std::index_sequence<I...>) {
  return (
      (a.downsample.factor == kBlurFactors[I] ? (film_kernel<kBlurFactors[I]><<<tiles, kThreads>>>(a), true) : false) ||
      ...);
}

}  // namespace

void cuda_twin(const SplatArgs& a) {
  const unsigned tiles = unsigned(splat_tile_count(a.grid));
  deposit_kernel<<<(a.capacity + kThreads - 1) / kThreads, kThreads>>>(a);
  check_launch("deposit_kernel");
  if (!a.downsample.low) {
    film_kernel<0><<<tiles, kThreads>>>(a);
  } else if (!launch_film_downsampled(a, tiles, std::make_index_sequence<std::size(kBlurFactors)>{})) {
    throw std::logic_error("splat: a downsample factor not in kBlurFactors");
  }
  check_launch("film_kernel");
}

}  // namespace bleedsim
