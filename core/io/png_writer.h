#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace bleedsim {

// Writes an RGBA8 image as PNG through a temporary file renamed into place, so a reader never
// sees half a file, every write checked and flushed to disk. Throws std::runtime_error naming the
// path and the OS error (a full disk, a file size limit) when it cannot.
// The same as encode_png_rgba, then write_png_file.
void write_png_rgba(const std::string& path, int width, int height, const std::uint8_t* rgba);

// An RGBA8 image encoded as PNG into `png` (overwritten). Safe from several threads at once; `path`
// only names the file in a failure's message.
void encode_png_rgba(const std::string& path, int width, int height, const std::uint8_t* rgba,
                     std::vector<unsigned char>& png);
// Encoded PNG bytes written to `path` as write_png_rgba writes them.
void write_png_file(const std::string& path, const std::vector<unsigned char>& png);

}  // namespace bleedsim
