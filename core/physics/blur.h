#pragma once
// Blur (the report's §2.2.2.5, after Rastertek): the film of blood is downsampled by a factor
// (1, 2 or 4), blurred by a separable Gaussian — a horizontal pass, then a vertical one — and
// upsampled back to the panel's pixels, so the particles' film reads as a soft layer.
//
// Every pass is a gather: each output element reads its inputs in a fixed order and sums them
// left to right, so both backends give the same bits. Edges clamp: a tap past the edge reads the
// edge pixel. The weights are computed once on the host and uploaded.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/physics/hd.h"
#include "core/physics/pixel_grid.h"

namespace bleedsim {

// The blur's sizes and buffers, which its passes share.
struct BlurArgs {
  int width;            // the panel, in pixels
  int height;
  int factor;           // downsample factor: 1, 2 or 4
  int low_width;        // ⌈width / factor⌉
  int low_height;
  int radius;           // taps either side, at the downsampled resolution
  const float* weights; // 2·radius + 1, summing to 1
  const float* film;    // width × height: splat/thickness
  float* low;           // low_width × low_height: downsampled, then blurred vertically
  float* across;        // low_width × low_height: blurred horizontally
  float* blurred;       // width × height: the result
};

// The blur's downsampling factors: the one list that [blur].downsample's range, the splat's CUDA
// launch (a kernel for each) and the study's ladder read. Each a power of two, so that a block's
// mean scales by an exact inverse (inverse_factor).
constexpr int kBlurFactors[] = {1, 2, 4};

// 1 / factor, exactly, for a power of two 2^k: its float's exponent field is 127 + k and the
// inverse's 127 − k, over the same zero mantissa, so the inverse's bits are 254·2²³ less the
// factor's. Multiplying by it rounds the same real number as dividing by the factor does, to the
// bit, and spares the pixel a division (a long sequence on the GPU), a loop or a test a factor.
BLEEDSIM_HD inline float inverse_factor(int factor) {
  const float f = float(factor);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  bits = 0x7F000000u - bits;
  float inverse;
  std::memcpy(&inverse, &bits, sizeof inverse);
  return inverse;
}

constexpr bool blur_factors_are_powers_of_two() {
  for (const int f : kBlurFactors)
    if (f <= 0 || (f & (f - 1)) != 0) return false;
  return true;
}
static_assert(blur_factors_are_powers_of_two(), "inverse_factor is exact only for powers of two");

// Downsample: the mean of the factor × factor block (the part of it inside the panel, at an edge),
// summed row by row, each left to right, film(x, y) giving the film at panel pixel (x, y). A whole
// block counts factor² pixels, a power of two: its exact inverse, as inverse_factor; and it needs
// no test of the panel's edge at each pixel.
template <class Film>
BLEEDSIM_HD inline float block_mean_of(const BlurArgs& a, int i, int j, const Film& film) {
  const int x0 = i * a.factor, y0 = j * a.factor;
  float sum = 0.0f;
  if (x0 + a.factor <= a.width && y0 + a.factor <= a.height) {
    for (int y = y0; y < y0 + a.factor; ++y)
      for (int x = x0; x < x0 + a.factor; ++x) sum += film(x, y);
    const float inverse = inverse_factor(a.factor);
    return sum * (inverse * inverse);
  }
  int count = 0;
  for (int y = y0; y < y0 + a.factor && y < a.height; ++y)
    for (int x = x0; x < x0 + a.factor && x < a.width; ++x, ++count) sum += film(x, y);
  return sum / float(count);
}

BLEEDSIM_HD inline float block_mean(const BlurArgs& a, int i, int j) {
  return block_mean_of(a, i, j, [&](int x, int y) { return a.film[std::size_t(y) * a.width + x]; });
}

// One pass of the separable Gaussian at (i, j): along the row, or down the column, the taps summed
// from the first to the last. Where every tap lies on the panel (all but `radius` pixels at either
// end of a line) they are read straight along the line, without the clamp an edge needs.
BLEEDSIM_HD inline float gaussian_tap_sum(const BlurArgs& a, const float* in, int i, int j, bool horizontal) {
  const int at = horizontal ? i : j, size = horizontal ? a.low_width : a.low_height;
  const std::size_t step = horizontal ? 1 : std::size_t(a.low_width);
  const float* line = in + (horizontal ? std::size_t(j) * a.low_width : std::size_t(i));  // the line's first pixel
  float sum = 0.0f;
  if (at >= a.radius && at + a.radius < size) {
    const float* tap = line + std::size_t(at - a.radius) * step;
    for (int k = 0; k <= 2 * a.radius; ++k, tap += step) sum += a.weights[k] * *tap;
  } else {
    for (int k = -a.radius; k <= a.radius; ++k)
      sum += a.weights[k + a.radius] * line[std::size_t(clamp_index(at + k, size)) * step];
  }
  return sum;
}

// Upsample: bilinear between the four nearest downsampled pixel centres (clamped at the edges).
BLEEDSIM_HD inline float bilinear_up(const BlurArgs& a, int i, int j) {
  const float inverse = inverse_factor(a.factor);
  const float x = (float(i) + 0.5f) * inverse - 0.5f;
  const float y = (float(j) + 0.5f) * inverse - 0.5f;
  const float x0f = floorf(x), y0f = floorf(y);
  const float fx = x - x0f, fy = y - y0f;
  const int x0 = clamp_index(int(x0f), a.low_width), x1 = clamp_index(int(x0f) + 1, a.low_width);
  const int y0 = clamp_index(int(y0f), a.low_height), y1 = clamp_index(int(y0f) + 1, a.low_height);
  const float* row0 = a.low + std::size_t(y0) * a.low_width;
  const float* row1 = a.low + std::size_t(y1) * a.low_width;
  const float top = row0[x0] + (row0[x1] - row0[x0]) * fx;
  const float bottom = row1[x0] + (row1[x1] - row1[x0]) * fx;
  return top + (bottom - top) * fy;
}

// The passes, pixel by pixel (core/physics/pixel_kernels.h runs them). Each writes one grid from
// another, never the one it reads.

// film → low, on the downsampled grid.
struct BlurDownsample {
  BlurArgs a;

  BLEEDSIM_HD int width() const { return a.low_width; }
  BLEEDSIM_HD int height() const { return a.low_height; }
  BLEEDSIM_HD void operator()(int i, int j) const { a.low[std::size_t(j) * a.low_width + i] = block_mean(a, i, j); }
};

// in → out along rows (horizontal) or columns, on the downsampled grid.
struct BlurGaussian {
  BlurArgs a;
  const float* in;
  float* out;
  bool horizontal;

  BLEEDSIM_HD int width() const { return a.low_width; }
  BLEEDSIM_HD int height() const { return a.low_height; }
  BLEEDSIM_HD void operator()(int i, int j) const {
    out[std::size_t(j) * a.low_width + i] = gaussian_tap_sum(a, in, i, j, horizontal);
  }
};

// low → blurred, on the panel's grid.
struct BlurUpsample {
  BlurArgs a;

  BLEEDSIM_HD int width() const { return a.width; }
  BLEEDSIM_HD int height() const { return a.height; }
  BLEEDSIM_HD void operator()(int i, int j) const { a.blurred[std::size_t(j) * a.width + i] = bilinear_up(a, i, j); }
};

// The four passes in the order they run: downsample film → low, horizontal low → across, vertical
// across → low, upsample low → blurred. The splat may have downsampled its film already, in its own
// pass (SplatArgs::downsample): then the three after it.
struct BlurPasses {
  BlurDownsample downsample;
  BlurGaussian horizontal;
  BlurGaussian vertical;
  BlurUpsample upsample;

  template <class Fn>
  void each(const Fn& fn, bool with_downsample = true) const {
    if (with_downsample) fn(downsample);
    fn(horizontal);
    fn(vertical);
    fn(upsample);
  }
};

inline BlurPasses blur_passes(const BlurArgs& a) {
  return {{a}, {a, a.low, a.across, true}, {a, a.across, a.low, false}, {a}};
}

}  // namespace bleedsim
