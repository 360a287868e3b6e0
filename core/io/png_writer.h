#pragma once
#include <cstdint>
#include <string>

namespace bleedsim {

// Writes an RGBA8 image as PNG through a temporary file renamed into place, so a reader never
// sees half a file. Throws std::runtime_error naming the path when it cannot.
void write_png_rgba(const std::string& path, int width, int height, const std::uint8_t* rgba);

}  // namespace bleedsim
