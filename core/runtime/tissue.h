#pragma once
// The procedural tissue: a mucosa drawn from a seed, for scenes that name no texture (a PNG
// texture is read by core/io/tissue_png.h).
#include <cstdint>
#include <vector>

#include "core/runtime/image.h"

namespace bleedsim {

// A pink mucosa with soft mottling and darker vessels, the same bytes for the same
// (width, height, seed) on every machine (integer hashing and polynomials only; no libm).
// Throws std::invalid_argument for a size that is not positive.
Image procedural_tissue(int width, int height, std::uint64_t seed);

// The same tissue's vessels as a density map, 0 to 1 per pixel (row by row): where
// procedural_tissue draws a vessel, in proportion to how strongly it draws it. Throws as it does.
std::vector<float> procedural_vessel_density(int width, int height, std::uint64_t seed);

}  // namespace bleedsim
