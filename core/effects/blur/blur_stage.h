#pragma once
// The blur of the particles' film (report §2.2.2.5): its stage, in blur_stage.cpp with the blur's row.
#include <vector>

namespace bleedsim {

// The Gaussian's taps for a radius and sigma (in downsampled pixels), in double, normalised to a
// sum of 1 and rounded once to float.
std::vector<float> gaussian_weights(int radius, double sigma);

}  // namespace bleedsim
