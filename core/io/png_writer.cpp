#include "core/io/png_writer.h"

#include <stb/stb_image_write.h>

#include <climits>
#include <stdexcept>
#include <vector>

#include "core/io/whole_file.h"

namespace bleedsim {
namespace {

void append(void* context, void* data, int size) {
  auto& bytes = *static_cast<std::vector<unsigned char>*>(context);
  bytes.insert(bytes.end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
}

}  // namespace

void write_png_rgba(const std::string& path, int width, int height, const std::uint8_t* rgba) {
  std::vector<unsigned char> png;
  encode_png_rgba(path, width, height, rgba, png);
  write_png_file(path, png);
}

void encode_png_rgba(const std::string& path, int width, int height, const std::uint8_t* rgba,
                     std::vector<unsigned char>& png) {
  if (width <= 0 || height <= 0 || width > INT_MAX / 4 || !rgba)
    throw std::invalid_argument("cannot write PNG '" + path + "': no image (" +
                                std::to_string(width) + "x" + std::to_string(height) + ")");
  // stb encodes with its own deterministic zlib at the default compression level; the level is a
  // global in stb, so it is left alone rather than set from several threads.
  png.clear();
  if (!stbi_write_png_to_func(append, &png, width, height, 4, rgba, width * 4))
    throw std::runtime_error("cannot write PNG '" + path + "': the encoder failed");
}

void write_png_file(const std::string& path, const std::vector<unsigned char>& png) {
  write_whole_file(path, png.data(), png.size(), "PNG");
}

}  // namespace bleedsim
