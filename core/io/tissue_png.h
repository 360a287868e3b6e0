#pragma once
// A tissue texture from a PNG file (docs/scenario-format.md, [tissue]).
#include <string>

#include "core/runtime/image.h"
#include "core/runtime/input_error.h"

namespace bleedsim {

// Loads a PNG (any channel count, 8 or 16 bit) as RGBA8 and resamples it bilinearly to
// width × height when its size differs. Throws InputError at `where`/`key` when it cannot,
// std::invalid_argument for a size that is not positive.
Image load_tissue_png(const std::string& path, int width, int height, const SourcePlace& where,
                      const std::string& key);

}  // namespace bleedsim
