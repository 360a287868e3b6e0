#pragma once
// The tissue the blood is drawn over: a PNG from the scenario, or a procedural mucosa.
#include <cstdint>
#include <string>

#include "core/image.h"
#include "core/input_error.h"

namespace bleedsim {

// A pink mucosa with soft mottling and darker vessels, the same bytes for the same
// (width, height, seed) on every machine (integer hashing and polynomials only; no libm).
// Throws std::invalid_argument for a size that is not positive.
Image procedural_tissue(int width, int height, std::uint64_t seed);

// Loads a PNG (any channel count, 8 or 16 bit) as RGBA8 and resamples it bilinearly to
// width × height when its size differs. Throws InputError at `where`/`key` when it cannot,
// std::invalid_argument for a size that is not positive.
Image load_tissue_png(const std::string& path, int width, int height, const SourcePlace& where,
                      const std::string& key);

}  // namespace bleedsim
