#pragma once
#include <cmath>
#include <cstddef>

#include "core/physics/hd.h"

namespace bleedsim {

// The panel as pixels: x to the right, y downwards, origin at the top-left corner.
// Pixel (i, j) covers [i, i+1) × [j, j+1) in pixel units; its centre is at (i + ½, j + ½).
struct PixelGrid {
  int width = 0;
  int height = 0;
  float mm_per_px_x = 1.0f;
  float mm_per_px_y = 1.0f;
};

BLEEDSIM_HD inline float pixel_centre_x_mm(const PixelGrid& g, int i) {
  return (static_cast<float>(i) + 0.5f) * g.mm_per_px_x;
}
BLEEDSIM_HD inline float pixel_centre_y_mm(const PixelGrid& g, int j) {
  return (static_cast<float>(j) + 0.5f) * g.mm_per_px_y;
}

// An index clamped to [0, size): a tap or neighbour past the edge reads the edge. A minimum and a
// maximum, which the GPU does in an instruction each (a nested choice became branches there).
BLEEDSIM_HD inline int clamp_index(int v, int size) {
  const int below_end = v < size - 1 ? v : size - 1;
  return below_end > 0 ? below_end : 0;
}

struct PixelAt {
  int i, j;
};

// The pixel holding (x, y), clamped to the panel (before the conversion: float→int of out-of-range
// values differs between CPU and GPU): its column and row, and its index.
BLEEDSIM_HD inline PixelAt pixel_at(const PixelGrid& g, float x, float y) {
  return {int(min_float(max_float(floorf(x / g.mm_per_px_x), 0.0f), float(g.width - 1))),
          int(min_float(max_float(floorf(y / g.mm_per_px_y), 0.0f), float(g.height - 1)))};
}
BLEEDSIM_HD inline std::size_t pixel_containing(const PixelGrid& g, float x, float y) {
  const PixelAt p = pixel_at(g, x, y);
  return std::size_t(p.j) * std::size_t(g.width) + std::size_t(p.i);
}

}  // namespace bleedsim
