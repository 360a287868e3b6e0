#include "core/io/png_writer.h"

#include <fcntl.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace bleedsim {
namespace {

void append(void* context, void* data, int size) {
  auto& bytes = *static_cast<std::vector<unsigned char>*>(context);
  bytes.insert(bytes.end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
}

// Every byte written, then flushed to disk and closed, each step checked: stb's own file writer
// ignores fwrite's result, so a full disk (ENOSPC) or a file size limit (EFBIG) left a short PNG
// that looked written. Returns 0, or the errno of the step that failed.
int write_whole_file(const std::string& path, const std::vector<unsigned char>& bytes) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int reason = errno;
      close(fd);
      return reason;
    }
    done += std::size_t(n);
  }
  const int synced = fsync(fd) == 0 ? 0 : errno;
  const int closed = close(fd) == 0 ? 0 : errno;
  return synced ? synced : closed;
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
  const std::string temporary = path + ".tmp";
  if (const int reason = write_whole_file(temporary, png)) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write PNG '" + path + "': " + std::strerror(reason));
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
