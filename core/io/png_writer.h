#pragma once
#include <cstdint>
#include <string>

namespace bleedsim {

// Writes an RGBA8 image as PNG through a temporary file renamed into place, so a reader never
// sees half a file, every write checked and flushed to disk. Throws std::runtime_error naming the
// path and the OS error (a full disk, a file size limit) when it cannot.
void write_png_rgba(const std::string& path, int width, int height, const std::uint8_t* rgba);

}  // namespace bleedsim
