#include "core/io/png_writer.h"

#include <stb/stb_image_write.h>

#include <cerrno>
#include <climits>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace bleedsim {

void write_png_rgba(const std::string& path, int width, int height, const std::uint8_t* rgba) {
  if (width <= 0 || height <= 0 || width > INT_MAX / 4 || !rgba)
    throw std::invalid_argument("cannot write PNG '" + path + "': no image (" +
                                std::to_string(width) + "x" + std::to_string(height) + ")");

  // stb writes with stdio and its own deterministic zlib at the default compression level; the
  // level is a global in stb, so it is left alone rather than set from several threads.
  const std::string temporary = path + ".tmp";
  errno = 0;
  if (!stbi_write_png(temporary.c_str(), width, height, 4, rgba, width * 4)) {
    const int reason = errno;  // from fopen/fwrite, when that is where stb failed
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(
        "cannot write PNG '" + path + "'" +
        (reason ? ": " + std::generic_category().message(reason) : std::string()));
  }

  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write PNG '" + path + "': " + error.message());
  }
}

}  // namespace bleedsim
