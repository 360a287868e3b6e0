#pragma once
// The per-pixel work of every stage, as functors: F{...}(i, j) writes pixel (i, j) of its output,
// of extent F::width() × F::height(), and reads only its inputs, so pixels can run in any order.
// One loop (reference_cpu/pixel_kernels.cpp) and one kernel (kernels/pixel_kernels.cu) run them
// all: a per-pixel effect needs only its functor, in its physics header, and a line here.
#include <stdexcept>

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
  X(TrailPixel)                   \
  X(TrailThenBlend)

namespace bleedsim {

// Two passes over the same pixels as one: at each pixel `first`, then `then`. Sound where the two
// have one extent and `then` reads what `first` writes only at its own pixel, which a thread sees
// as it wrote it. The frame's pixel passes are bound by the instructions they issue and the bytes
// they move: one pass spares a launch and the second reading of what the first wrote.
template <class First, class Then>
struct PixelPair {
  First first;
  Then then;

  BLEEDSIM_HD int width() const { return then.width(); }
  BLEEDSIM_HD int height() const { return then.height(); }
  BLEEDSIM_HD void operator()(int i, int j) const {
    first(i, j);
    then(i, j);
  }
};

template <class First, class Then>
PixelPair<First, Then> pair_pixels(const First& first, const Then& then) {
  if (first.width() != then.width() || first.height() != then.height())
    throw std::logic_error("pair_pixels: the two passes cover different pixels");
  return {first, then};
}

// The trail's drying and wetting in the blend's pass (BlendStage): the blend reads the residue
// only at its own pixel.
using TrailThenBlend = PixelPair<TrailPixel, BlendPixel>;

// The twins of each: over host memory on `threads` threads, and over device memory.
#define BLEEDSIM_DECLARE_PIXEL_TWINS(F) \
  void cpu_twin(const F& f, int threads); \
  void cuda_twin(const F& f);
BLEEDSIM_PIXEL_KERNELS(BLEEDSIM_DECLARE_PIXEL_TWINS)
#undef BLEEDSIM_DECLARE_PIXEL_TWINS

}  // namespace bleedsim
