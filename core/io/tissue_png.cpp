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
constexpr std::size_t kHeaderBytes = 29;  // the signature, then IHDR's length, type and 13 bytes of data

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

// The channels a colour type stores (a palette's index is one), and the bit depths PNG allows it.
struct ColourType {
  int type;
  int channels;
  std::vector<int> depths;
};

const ColourType* colour_type(int type) {
  static const ColourType kTypes[] = {
      {0, 1, {1, 2, 4, 8, 16}}, {2, 3, {8, 16}}, {3, 1, {1, 2, 4, 8}}, {4, 2, {8, 16}}, {6, 4, {8, 16}}};
  for (const ColourType& t : kTypes)
    if (t.type == type) return &t;
  return nullptr;
}

// The width and height the first kHeaderBytes state, checked against the cap, and how the pixels
// are stored.
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
  const int depth = bytes[24], type = bytes[25], interlace = bytes[28];
  const ColourType* colour = colour_type(type);
  if (!colour || std::find(colour->depths.begin(), colour->depths.end(), depth) == colour->depths.end())
    throw undecodable(file, "its header states colour type " + std::to_string(type) + " at " + std::to_string(depth) +
                                " bits, which PNG does not have");
  if (interlace > 1) throw undecodable(file, "its header states interlace method " + std::to_string(interlace) +
                                                 ", which PNG does not have");
  return {int(width), int(height), depth, type, interlace == 1, size};
}

// The bytes a w x h image's filtered rows take: a filter byte and the packed samples, each row.
std::uint64_t rows_bytes(std::int64_t w, std::int64_t h, int bits_per_pixel) {
  if (w <= 0 || h <= 0) return 0;
  return std::uint64_t(h) * ((std::uint64_t(w) * std::uint64_t(bits_per_pixel) + 7) / 8 + 1);
}

// What the image data inflates to: the rows, or the rows of Adam7's seven passes.
std::uint64_t image_data_bytes(const TextureHeader& h) {
  const int bits = h.bit_depth * colour_type(h.colour_type)->channels;
  if (!h.interlaced) return rows_bytes(h.width, h.height, bits);
  constexpr int x0[] = {0, 4, 0, 2, 0, 1, 0}, y0[] = {0, 0, 4, 0, 2, 0, 1};
  constexpr int dx[] = {8, 8, 4, 4, 2, 2, 1}, dy[] = {8, 8, 8, 4, 4, 2, 2};
  std::uint64_t bytes = 0;
  for (int p = 0; p < 7; ++p)
    bytes += rows_bytes((h.width - x0[p] + dx[p] - 1) / dx[p], (h.height - y0[p] + dy[p] - 1) / dy[p], bits);
  return bytes;
}

// stb_image trusts a PNG further than its header: it allocates an IDAT chunk's stated length before
// reading it, and inflates the image data into a buffer it doubles for as long as the stream goes
// on. So, before stb sees the file, every chunk must lie inside it, and the image data must inflate
// to no more than the rows the header states (what texture_memory() counts): a 400-byte file that
// claimed a 2 GB chunk made stb ask for 2 GB (found by fuzz/tissue_png_fuzzer), and a small file of
// compressed zeros can inflate a thousandfold.
void check_chunks(const unsigned char* bytes, std::size_t size, const TextureHeader& header, const InputFile& file) {
  const Count most = image_data_bytes(header);
  z_stream inflater{};
  bool inflating = false, stream_checked = false;
  std::uint64_t inflated = 0;
  unsigned char scratch[1 << 14];
  for (std::size_t at = sizeof kSignature; at < size;) {
    // stb reads a chunk's length from a file's last few bytes too (a 43-byte file whose last 10
    // bytes claimed a 1 GiB IDAT made it ask for 1 GiB; fuzz/tissue_png_fuzzer).
    if (size - at < 12) {
      if (inflating) inflateEnd(&inflater);
      throw undecodable(file, "it ends inside a chunk: " + std::to_string(size - at) +
                                  " bytes are left, less than a chunk's length, type and CRC");
    }
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

}  // namespace

TextureHeader read_tissue_png_header(const InputFile& file) {
  std::ifstream in = open_input(file);
  unsigned char bytes[kHeaderBytes] = {};
  in.read(reinterpret_cast<char*>(bytes), kHeaderBytes);
  TextureHeader header = parse_header(bytes, std::size_t(in.gcount()), file);
  std::error_code ec;
  header.file_bytes = std::filesystem::file_size(file.path, ec);
  if (ec) throw unreadable(file, ec.value());
  return header;
}

MemoryPart texture_memory(const TextureHeader& header, const InputFile& file, int width, int height) {
  // What stb_image v2.27 holds at once, phase by phase (stbi__parse_png_file, stbi__do_png):
  const Count pixels = Count(header.width) * Count(header.height);
  const int bytes_per_channel = header.bit_depth == 16 ? 2 : 1;
  // the IDAT chunks, gathered into a buffer that doubles from 4 KiB (at a doubling, the old beside
  // the new);
  const Count file_bytes = header.file_bytes;
  const Count gathered = Count(2) * file_bytes + 4096;
  // the inflated rows beside them, in a buffer of the non-interlaced size: Adam7's passes take a
  // little more, so for them it doubles once (the old beside the new);
  const Count guess = rows_bytes(header.width, header.height, header.bit_depth * colour_type(header.colour_type)->channels);
  const Count inflated = header.interlaced ? Count(2) * guess : guess;
  // the unfiltered image, with the channels stored and an alpha for a tRNS chunk (grey, RGB), beside
  // the rows; de-interlacing holds the whole image beside a pass's, the largest W x ⌈H/2⌉;
  const int first_channels = header.colour_type == 0 ? 2 : header.colour_type == 2 ? 4 : colour_type(header.colour_type)->channels;
  const Count pixel_bytes = first_channels * bytes_per_channel;
  const Count first = pixels * pixel_bytes;
  const Count unfiltered =
      header.interlaced ? first + Count(header.width) * Count((header.height + 1) / 2) * pixel_bytes : first;
  // the image converted to RGBA (a palette expanded), then 16 bits narrowed to 8, each beside the
  // one before;
  const Count rgba = pixels * 4;
  const Count widened = first_channels == 4 ? Count(0) : first + rgba * Count(bytes_per_channel);
  const Count narrowed = bytes_per_channel == 2 ? rgba * 2 + rgba : Count(0);
  // then ours: the RGBA beside its copy, or beside the panel resampled from it.
  const bool resamples = header.width != width || header.height != height;
  const Count resampled =
      rgba + (resamples ? Count(width) * Count(height) * 4 + (Count(width) + Count(height)) * sizeof(Tap) : rgba);
  const Count most = std::max({file_bytes + gathered, gathered + (header.interlaced ? Count(3) * guess : guess),
                               inflated + unfiltered, widened, narrowed, resampled});
  return {file.key,
          "decoding the " + std::to_string(header.width) + " x " + std::to_string(header.height) + " px " + file.what +
              " '" + file.path + "'",
          file_bytes + most};
}

Image load_tissue_png(const InputFile& file, int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("load_tissue_png: width and height must be positive (got " +
                                std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  // The header first, so that a file too large to decode is refused before it is read.
  const TextureHeader header = read_tissue_png_header(file);
  std::ifstream in = open_input(file);
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
  const MemoryPart need = texture_memory(header, file, width, height);
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
