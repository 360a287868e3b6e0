#include "core/io/tissue_png.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

namespace bleedsim {
namespace {

// ---- PNG resampling ---------------------------------------------------------------------------
// Bilinear, in exact integer arithmetic. Destination pixel i has its centre at source coordinate
// (i + ½)·src/dst − ½ = num/den with den = 2·dst: the two source pixels around it and the weight
// of the upper one, num mod den, are exact, and the edges clamp.
struct Tap {
  int lo;
  int hi;
  std::int64_t weight_hi;  // out of den; the lower pixel weighs den − weight_hi
};

std::vector<Tap> bilinear_taps(int src, int dst) {
  const std::int64_t den = 2 * std::int64_t{dst};
  std::vector<Tap> taps(static_cast<std::size_t>(dst));
  for (int i = 0; i < dst; ++i) {
    const std::int64_t num = (2 * std::int64_t{i} + 1) * src - dst;
    std::int64_t lo = num / den;
    if (num % den < 0) --lo;  // floor, not truncation: the first centres lie left of pixel 0's
    const std::int64_t weight = num - lo * den;
    const auto clamp = [src](std::int64_t k) {
      return static_cast<int>(std::clamp<std::int64_t>(k, 0, src - 1));
    };
    taps[static_cast<std::size_t>(i)] = Tap{clamp(lo), clamp(lo + 1), weight};
  }
  return taps;
}

Image resample_bilinear(const std::uint8_t* src, int src_w, int src_h, int width, int height) {
  const std::vector<Tap> xs = bilinear_taps(src_w, width);
  const std::vector<Tap> ys = bilinear_taps(src_h, height);
  const std::int64_t den_x = 2 * std::int64_t{width};
  const std::int64_t den_y = 2 * std::int64_t{height};
  const std::int64_t den = den_x * den_y;  // at most 2^34: 255·den fits comfortably in 64 bits
  const auto at = [src, src_w](int x, int y, int channel) -> std::int64_t {
    return src[(std::size_t(y) * std::size_t(src_w) + std::size_t(x)) * 4 + std::size_t(channel)];
  };

  Image out{width, height, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4)};
  for (int j = 0; j < height; ++j) {
    const Tap& ty = ys[static_cast<std::size_t>(j)];
    const std::int64_t wy_hi = ty.weight_hi;
    const std::int64_t wy_lo = den_y - wy_hi;
    for (int i = 0; i < width; ++i) {
      const Tap& tx = xs[static_cast<std::size_t>(i)];
      const std::int64_t wx_hi = tx.weight_hi;
      const std::int64_t wx_lo = den_x - wx_hi;
      std::uint8_t* pixel = &out.rgba[(std::size_t(j) * std::size_t(width) + std::size_t(i)) * 4];
      for (int c = 0; c < 4; ++c) {
        const std::int64_t sum =
            wx_lo * wy_lo * at(tx.lo, ty.lo, c) + wx_hi * wy_lo * at(tx.hi, ty.lo, c) +
            wx_lo * wy_hi * at(tx.lo, ty.hi, c) + wx_hi * wy_hi * at(tx.hi, ty.hi, c);
        pixel[c] = static_cast<std::uint8_t>((sum + den / 2) / den);  // round half up
      }
    }
  }
  return out;
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
struct StbFree {
  void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};

}  // namespace

Image load_tissue_png(const std::string& path, int width, int height, const SourcePlace& where,
                      const std::string& key) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("load_tissue_png: width and height must be positive (got " +
                                std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  // Opened here rather than by stb, so a missing file is reported with the system's reason.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(where, key, "cannot read texture '" + path + "': it is a folder");
  errno = 0;
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) {
    throw InputError(where, key,
                     "cannot read texture '" + path + "': " + std::strerror(errno ? errno : ENOENT));
  }
  int src_w = 0;
  int src_h = 0;
  int channels_in_file = 0;
  const std::unique_ptr<stbi_uc, StbFree> pixels(
      stbi_load_from_file(file.get(), &src_w, &src_h, &channels_in_file, 4));
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    throw InputError(where, key,
                     "cannot decode texture '" + path + "' as a PNG: " +
                         (reason ? reason : "unknown error"));
  }
  if (src_w == width && src_h == height) {
    const std::size_t bytes = std::size_t(width) * std::size_t(height) * 4;
    return Image{width, height, std::vector<std::uint8_t>(pixels.get(), pixels.get() + bytes)};
  }
  return resample_bilinear(pixels.get(), src_w, src_h, width, height);
}

}  // namespace bleedsim
