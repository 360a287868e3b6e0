#pragma once
// A tissue texture from a PNG file (docs/scenario-format.md, [tissue]).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "core/runtime/image.h"
#include "core/runtime/input_error.h"
#include "core/runtime/memory.h"

namespace bleedsim {

// The largest texture, on a side: a 16384 x 16384 PNG already decodes to 1 GiB of RGBA.
constexpr int kMaxTextureSide = 16384;

// What a PNG's header says, read without decoding anything.
struct TextureHeader {
  int width = 0;
  int height = 0;
  std::uint64_t file_bytes = 0;
};

// Reads the signature and the IHDR chunk of `path` (24 bytes): throws InputError at `where`/`key`
// when it cannot be read, is not a PNG, or states more than kMaxTextureSide pixels on a side.
TextureHeader read_tissue_png_header(const std::string& path, const SourcePlace& where, const std::string& key);

// The host memory decoding it takes, under `key`: the file, the inflated rows (which stb may hold
// twice over while it grows them) and the decoded image, at 16 bits per channel at worst.
MemoryPart texture_memory(const TextureHeader& header, const std::string& key);

// Loads a PNG (any channel count, 8 or 16 bit) as RGBA8 and resamples it bilinearly to
// width × height when its size differs. Throws InputError at `where`/`key` when it cannot,
// std::invalid_argument for a size that is not positive.
Image load_tissue_png(const std::string& path, int width, int height, const SourcePlace& where,
                      const std::string& key);

// The same from the file's bytes (`name` names it in messages), refusing, before decoding, a header
// past the cap or whose decoding needs more than `room` bytes.
Image decode_tissue_png(const std::string& bytes, const std::string& name, int width, int height,
                        const SourcePlace& where, const std::string& key,
                        std::size_t room = std::numeric_limits<std::size_t>::max());

}  // namespace bleedsim
