#pragma once
// The per-pixel work of every stage, as functors: F{...}(i, j) writes pixel (i, j) of its output,
// of extent F::width() × F::height(), and reads only its inputs, so pixels can run in any order.
// One loop (reference_cpu/pixel_kernels.cpp) and one kernel (kernels/pixel_kernels.cu) run them
// all: a per-pixel effect needs only its functor, in its physics header, and a line here.
#include "core/physics/blend.h"
#include "core/physics/blur.h"
#include "core/physics/splat.h"
#include "core/physics/spread.h"
#include "core/physics/trail.h"

#define BLEEDSIM_PIXEL_KERNELS(X) \
  X(SpreadPixel)                  \
  X(SpreadSettle)                 \
  X(BlendPixel)                   \
  X(FixedLightPixel)              \
  X(BlurDownsample)               \
  X(BlurGaussian)                 \
  X(BlurUpsample)                 \
  X(SplatThickness)               \
  X(TrailPixel)

namespace bleedsim {

// The twins of each: over host memory on `threads` threads, and over device memory.
#define BLEEDSIM_DECLARE_PIXEL_TWINS(F) \
  void cpu_twin(const F& f, int threads); \
  void cuda_twin(const F& f);
BLEEDSIM_PIXEL_KERNELS(BLEEDSIM_DECLARE_PIXEL_TWINS)
#undef BLEEDSIM_DECLARE_PIXEL_TWINS

}  // namespace bleedsim
