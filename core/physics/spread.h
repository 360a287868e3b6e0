#pragma once
// Texture-based radial spread of blood from cut points (report §2.2.1).
//
// A cut of radius r leaves, at distance d from its centre, a final stain ((r − d)/r)^6: 1 at the
// centre, a soft edge falling to 0 at r. The stain grows towards that final value over time; all
// pixels of one cut grow in proportion (as in the report, where every pixel's increment is its
// final value times a common factor), so a cut's state at any moment is one amplitude in [0, 1]
// and the visible edge, where the stain crosses a threshold, moves outwards as it grows.
// On a tissue mesh the distance is the surface's, through the pixel's frame (core/physics/surface.h).
// Several stains combine as independent absorbers: the light left after all of them is the
// product of what each lets through, stain = 1 − Π(1 − sᵢ), taken in cut order.
//
// A frame's pixels multiply in only the cuts near them: the panel is cut into square tiles, and a
// pixel walks the list of its tile, the cuts whose stain may reach some pixel of it (SpreadTiles).
// Skipping a cut is exact: its stain at the pixel is exactly 0, and light · (1 − 0) is light to the
// bit; the lists keep the cuts' order. So the bytes are those of the product over every cut, and a
// pixel's cost follows the cuts that overlap it, not how many are live.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/physics/hd.h"
#include "core/physics/pixel_grid.h"
#include "core/physics/surface.h"

namespace bleedsim {

// One cut as the spread sees it in one frame (mm; amplitude from cut_amplitude()). Aligned to its
// 16 bytes, so every pixel reads a cut in one load rather than four.
struct alignas(16) SpreadCut {
  float x_mm;
  float y_mm;
  float radius_mm;
  float amplitude;
};

// Integer power by multiplication: powf differs between the host's libm and the device.
BLEEDSIM_HD inline float sixth_power(float q) {
  const float q2 = q * q;
  const float q3 = q2 * q;
  return q3 * q3;
}

// The report's final stain at distance d from the centre of a cut of radius r.
BLEEDSIM_HD inline float stain_profile(float d, float r) {
  return d < r ? sixth_power((r - d) / r) : 0.0f;
}

// `frame`: the surface's at (x, y), or null on the flat panel.
BLEEDSIM_HD inline float cut_stain(const SpreadCut& cut, float x_mm, float y_mm, const SurfaceFrame* frame = nullptr) {
  float dx = x_mm - cut.x_mm;
  float dy = y_mm - cut.y_mm;
  if (frame) to_surface(*frame, dx, dy, &dx, &dy);
  // Outside the cut's bounding square the stain is 0: skip the square root.
  if (fabsf(dx) >= cut.radius_mm || fabsf(dy) >= cut.radius_mm) return 0.0f;
  return stain_profile(sqrtf(dx * dx + dy * dy), cut.radius_mm) * cut.amplitude;
}

// The light left at pixel (i, j) after `light_left` (from the cuts before these) and then each of
// the cuts cut_at(0), …, cut_at(count − 1) in order: light_left · Π(1 − sᵢ), one product at a time.
template <class CutAt>
BLEEDSIM_HD inline float light_through_each(int count, const CutAt& cut_at, const PixelGrid& grid, int i, int j,
                                            const SurfaceMap& surface, float light_left) {
  const float x = pixel_centre_x_mm(grid, i);
  const float y = pixel_centre_y_mm(grid, j);
  const SurfaceFrame frame = curved(surface) ? frame_of(surface, std::size_t(j) * grid.width + i) : SurfaceFrame{};
  const SurfaceFrame* on = curved(surface) ? &frame : nullptr;
  for (int c = 0; c < count; ++c) light_left *= 1.0f - cut_stain(cut_at(c), x, y, on);
  return light_left;
}

// The same over cuts[0 … cut_count − 1].
BLEEDSIM_HD inline float light_through(const SpreadCut* cuts, int cut_count, const PixelGrid& grid, int i, int j,
                                       const SurfaceMap& surface, float light_left) {
  return light_through_each(cut_count, [&](int c) { return cuts[c]; }, grid, i, j, surface, light_left);
}

// The spread's tiles: squares of kSpreadTilePx pixels from the panel's top-left corner, those of the
// last column and row cut short by its edge. 32: a GPU warp (32 neighbouring pixels of one row, in
// blocks of 32 × 8, kernels/pixel_kernels.cu) lies in one tile, so its threads walk one list together.
constexpr int kSpreadTilePx = 32;

// A frame's tile table, in compressed rows: tile t lists cut[first[t]] … cut[first[t + 1] − 1],
// indices into the frame's cuts in ascending order (the list's), of every cut whose stain may reach
// a pixel of t. Built on the host with a margin far beyond float rounding (core/effects/spread/spread_tiles.h),
// so a cut left out of a tile's list stains none of its pixels.
struct SpreadTiles {
  const int* first;  // tiles + 1 offsets into cut
  const int* cut;    // first[tiles] indices into the cuts
  int across;        // tiles per row: ⌈width / kSpreadTilePx⌉
};

BLEEDSIM_HD inline int tile_of(const SpreadTiles& tiles, int i, int j) {
  return (j / kSpreadTilePx) * tiles.across + i / kSpreadTilePx;
}

// As light_through over every cut, multiplying in only those listed for the pixel's tile: the
// others would each multiply by exactly 1 − 0. Each listed cut is read whole, as a copy: one 16-byte
// load on the GPU (by reference it was three, and the pixel's frame went to local memory).
BLEEDSIM_HD inline float light_through(const SpreadCut* cuts, const SpreadTiles& tiles, const PixelGrid& grid, int i,
                                       int j, const SurfaceMap& surface, float light_left) {
  const int t = tile_of(tiles, i, j), first = tiles.first[t];
  const int* listed = tiles.cut + first;
  return light_through_each(tiles.first[t + 1] - first, [&](int k) { return cuts[listed[k]]; }, grid, i, j, surface,
                            light_left);
}

// The combined stain of every cut at pixel (i, j).
BLEEDSIM_HD inline float spread_stain(const SpreadCut* cuts, int cut_count, const PixelGrid& grid,
                                      int i, int j, const SurfaceMap& surface = {}) {
  return 1.0f - light_through(cuts, cut_count, grid, i, j, surface, 1.0f);
}

// How far a cut's stain has grown at time t: 0 before it starts, then linear at growth_per_s
// (fraction of the final stain per second) until it is full. Host only: computed once per cut and
// frame, in double, and handed to both backends as the same float.
inline float cut_amplitude(double start_s, double growth_per_s, double t_s) {
  return static_cast<float>(std::clamp((t_s - start_s) * growth_per_s, 0.0, 1.0));
}

// The stage's work, pixel by pixel: the stain of one frame's cuts (core/physics/pixel_kernels.h runs it),
// each pixel through its tile's list. With `settled`, the light the cuts before these (whose stains
// no longer change) let through, from SpreadSettle: the same products in the same order as from
// every cut, so the same bytes. Built by SpreadUpload::pixel_work (core/effects/spread/spread_tiles.h).
struct SpreadPixel {
  const SpreadCut* cuts;
  SpreadTiles tiles;  // over these cuts
  PixelGrid grid;
  float* stain;  // grid.width × grid.height, row-major
  SurfaceMap surface = {};  // a tissue mesh's maps; empty on the flat panel
  const float* settled = nullptr;  // grid.width × grid.height, or none: 1 everywhere

  BLEEDSIM_HD int width() const { return grid.width; }
  BLEEDSIM_HD int height() const { return grid.height; }
  BLEEDSIM_HD void operator()(int i, int j) const {
    const std::size_t p = std::size_t(j) * grid.width + i;
    stain[p] = 1.0f - light_through(cuts, tiles, grid, i, j, surface, settled ? settled[p] : 1.0f);
  }
};

// Cuts whose stains no longer change, folded once into the light they let through, cut by cut in
// order, over a box of pixels that holds every pixel they stain (outside it each would multiply by
// 1 − 0, which changes nothing). A frame then costs its live cuts, not every cut ever made.
struct SpreadSettle {
  const SpreadCut* cuts;
  int cut_count;
  PixelGrid grid;
  float* settled;  // grid.width × grid.height
  SurfaceMap surface;
  int first_i, first_j, box_width, box_height;

  BLEEDSIM_HD int width() const { return box_width; }
  BLEEDSIM_HD int height() const { return box_height; }
  BLEEDSIM_HD void operator()(int i, int j) const {
    const int x = first_i + i, y = first_j + j;
    float& light = settled[std::size_t(y) * grid.width + x];
    light = light_through(cuts, cut_count, grid, x, y, surface, light);
  }
};

}  // namespace bleedsim
