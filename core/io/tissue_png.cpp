#include "core/io/tissue_png.h"

#include <stb/stb_image.h>
#define ZLIB_CONST  // next_in points at bytes zlib only reads
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <stdexcept>
#include <vector>

#include "core/runtime/count.h"

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

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::size_t kHeaderBytes = 24;  // the signature, then IHDR's length, type, width, height

struct StbFree {
  void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};

std::uint32_t big_endian(const unsigned char* at) {
  return std::uint32_t(at[0]) << 24 | std::uint32_t(at[1]) << 16 | std::uint32_t(at[2]) << 8 | at[3];
}

// "cannot decode <what> '<path>' as a PNG: <why>".
InputError undecodable(const InputFile& file, const std::string& why) {
  return InputError(file.where, file.key, "cannot decode " + file.what + " '" + file.path + "' as a PNG: " + why);
}

// The width and height the first kHeaderBytes state, checked against the cap.
TextureHeader parse_header(const unsigned char* bytes, std::size_t size, const InputFile& file) {
  if (size < kHeaderBytes || std::memcmp(bytes, kSignature, sizeof kSignature) != 0 ||
      std::memcmp(bytes + 12, "IHDR", 4) != 0)
    throw undecodable(file, "it does not start with a PNG signature and header");
  const std::uint32_t width = big_endian(bytes + 16), height = big_endian(bytes + 20);
  if (width == 0 || height == 0) throw undecodable(file, "its header states a size of 0");
  if (width > std::uint32_t(kMaxTextureSide) || height > std::uint32_t(kMaxTextureSide))
    throw InputError(file.where, file.key,
                     file.what + " '" + file.path + "' is " + std::to_string(width) + " x " + std::to_string(height) +
                         " px; a " + file.what + " may be at most " + std::to_string(kMaxTextureSide) +
                         " px on a side (it is resampled to the panel anyway)");
  return {int(width), int(height), size};
}

// stb_image trusts a PNG further than its header: it allocates an IDAT chunk's stated length before
// reading it, and inflates the image data into a buffer it doubles for as long as the stream goes
// on. So, before stb sees the file, every chunk must lie inside it, and the image data must inflate
// to no more than the rows the header states (counted by texture_memory()): a 400-byte file that
// claimed a 2 GB chunk made stb ask for 2 GB (found by fuzz/tissue_png_fuzzer), and a small file of
// compressed zeros can inflate a thousandfold.
void check_chunks(const unsigned char* bytes, std::size_t size, const TextureHeader& header, const InputFile& file) {
  const Count most = Count(2) * Count(header.height) * (Count(header.width) * 8 + 1);
  z_stream inflater{};
  bool inflating = false, stream_checked = false;
  std::uint64_t inflated = 0;
  unsigned char scratch[1 << 14];
  for (std::size_t at = sizeof kSignature; at + 12 <= size;) {
    const std::uint32_t length = big_endian(bytes + at);
    const std::string type(reinterpret_cast<const char*>(bytes + at + 4), 4);
    if (length > size - at - 12) {
      if (inflating) inflateEnd(&inflater);
      throw undecodable(file, "a chunk claims " + std::to_string(length) + " bytes, more than the file holds after it");
    }
    if (type == "CgBI") stream_checked = true;  // Apple's raw deflate: left to stb, whose size it bounds
    if (type == "IDAT" && !stream_checked) {
      if (!inflating && inflateInit(&inflater) != Z_OK) throw std::bad_alloc();
      inflating = true;
      inflater.next_in = bytes + at + 8;
      inflater.avail_in = length;
      while (inflater.avail_in > 0) {
        inflater.next_out = scratch;
        inflater.avail_out = sizeof scratch;
        const int status = inflate(&inflater, Z_NO_FLUSH);
        inflated += sizeof scratch - inflater.avail_out;
        if (Count(inflated) > most) {
          inflateEnd(&inflater);
          throw undecodable(file, "its image data inflates to more than the " + std::to_string(header.width) + " x " +
                                      std::to_string(header.height) + " px its header states");
        }
        // The stream's end, or an error stb will report: nothing more to count.
        if (status != Z_OK) {
          stream_checked = true;
          break;
        }
      }
    }
    if (type == "IEND") break;
    at += 12 + std::size_t(length);
  }
  if (inflating) inflateEnd(&inflater);
}

// For a file that cannot be opened or read: the OS's reason.
InputError unreadable(const InputFile& file, int error) { return unreadable(file, std::strerror(error ? error : EIO)); }

std::ifstream open_png(const InputFile& file) {
  require_regular_file(file);
  errno = 0;
  std::ifstream in(file.path, std::ios::binary);
  if (!in) throw unreadable(file, errno ? errno : ENOENT);
  return in;
}

}  // namespace

TextureHeader read_tissue_png_header(const InputFile& file) {
  std::ifstream in = open_png(file);
  unsigned char bytes[kHeaderBytes] = {};
  in.read(reinterpret_cast<char*>(bytes), kHeaderBytes);
  TextureHeader header = parse_header(bytes, std::size_t(in.gcount()), file);
  std::error_code ec;
  header.file_bytes = std::filesystem::file_size(file.path, ec);
  if (ec) throw unreadable(file, ec.value());
  return header;
}

MemoryPart texture_memory(const TextureHeader& header, const InputFile& file) {
  // Inflated: a filter byte and up to 4 channels of 2 bytes per pixel, each row; stb grows its buffer
  // by doubling, so up to twice that. Decoded: 4 channels of up to 2 bytes, and the 8-bit copy.
  const Count pixels = Count(header.width) * Count(header.height);
  const Count inflated = Count(2) * Count(header.height) * (Count(header.width) * 8 + 1);
  return {file.key,
          "decoding the " + std::to_string(header.width) + " x " + std::to_string(header.height) + " px " + file.what,
          Count(header.file_bytes) + inflated + pixels * (8 + 4)};
}

Image load_tissue_png(const InputFile& file, int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("load_tissue_png: width and height must be positive (got " +
                                std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  // The header first, so that a file too large to decode is refused before it is read.
  const TextureHeader header = read_tissue_png_header(file);
  std::ifstream in = open_png(file);
  std::string bytes(header.file_bytes, '\0');
  errno = 0;
  if (!in.read(bytes.data(), std::streamsize(bytes.size()))) throw unreadable(file, errno);
  return decode_tissue_png(bytes, file, width, height);
}

Image decode_tissue_png(const std::string& bytes, const InputFile& file, int width, int height, std::size_t room) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("decode_tissue_png: width and height must be positive (got " +
                                std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const TextureHeader header = parse_header(data, bytes.size(), file);
  const MemoryPart need = texture_memory(header, file);
  if (need.bytes > Count(room))
    throw InputError(file.where, file.key,
                     need.what + " '" + file.path + "' needs " + human_bytes(need.bytes.as_double()) +
                         " of host memory, but only " + human_bytes(double(room)) + " is available");
  if (bytes.size() > std::size_t(std::numeric_limits<int>::max()))
    throw undecodable(file, "the file is larger than 2 GiB");
  check_chunks(data, bytes.size(), header, file);
  int src_w = 0;
  int src_h = 0;
  int channels_in_file = 0;
  const std::unique_ptr<stbi_uc, StbFree> pixels(
      stbi_load_from_memory(data, int(bytes.size()), &src_w, &src_h, &channels_in_file, 4));
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    throw undecodable(file, reason ? reason : "unknown error");
  }
  if (src_w == width && src_h == height) {
    const std::size_t bytes_out = (Count(width) * Count(height) * 4).to<std::size_t>();
    return Image{width, height, std::vector<std::uint8_t>(pixels.get(), pixels.get() + bytes_out)};
  }
  return resample_bilinear(pixels.get(), src_w, src_h, width, height);
}

}  // namespace bleedsim
