#pragma once
// The blur of the particles' film (report §2.2.2.5; docs/particles.md, "The blur").
#include "core/runtime/params.h"

namespace bleedsim {

template <class P>
struct Effect;

// Present in a Scene only when the scene calls for it; it blurs the film the particles make.
struct BlurParams {
  int downsample = 2;     // one of kBlurFactors (core/physics/blur.h)
  int radius_px = 4;      // taps either side, in downsampled pixels
  double sigma_px = 2.0;  // the Gaussian's, in downsampled pixels
};

const ParamTable<BlurParams>& blur_table();
// Its row: the blur stage (blur_stage.cpp).
const Effect<BlurParams>& blur_effect();

}  // namespace bleedsim
