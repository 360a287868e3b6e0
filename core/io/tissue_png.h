#pragma once
// A tissue texture from a PNG file (docs/scenario-format.md, [tissue]).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "core/runtime/image.h"
#include "core/runtime/input_file.h"
#include "core/runtime/memory.h"

namespace bleedsim {

// The largest texture, on a side: a 16384 x 16384 PNG already decodes to 1 GiB of RGBA.
constexpr int kMaxTextureSide = 16384;

// What a PNG's header says, read without decoding anything.
struct TextureHeader {
  int width = 0;
  int height = 0;
  int bit_depth = 8;    // bits per channel (per palette index for colour type 3)
  int colour_type = 6;  // 0 grey, 2 RGB, 3 palette, 4 grey and alpha, 6 RGBA
  bool interlaced = false;
  std::uint64_t file_bytes = 0;
};

// The PNG files are a texture or a vessel map: messages name the file as what it is ("cannot read
// vessel map 'v.png'"), at the key that named it.

// Reads the signature and the IHDR chunk of the file (33 bytes): throws InputError when it is not a
// regular file, cannot be read, is not a PNG, states a bit depth and colour type PNG does not have,
// or more than kMaxTextureSide pixels on a side.
TextureHeader read_tissue_png_header(const InputFile& file);

// The most host memory loading it for a width x height panel holds at once, under the file's key:
// the file's bytes beside the largest of the buffers stb_image (v2.27) and the resampling hold
// together, from the header's size, bit depth, colour type and interlacing.
MemoryPart texture_memory(const TextureHeader& header, const InputFile& file, int width, int height);

// Loads a PNG (any channel count, 8 or 16 bit) as RGBA8 and resamples it bilinearly to
// width × height when its size differs. Throws InputError when it cannot, std::invalid_argument for
// a size that is not positive.
Image load_tissue_png(const InputFile& file, int width, int height);

// The same from the file's bytes (`file.path` names it in messages), refusing, before decoding, a
// header past the cap or whose decoding needs more than `room` bytes.
Image decode_tissue_png(const std::string& bytes, const InputFile& file, int width, int height,
                        std::size_t room = std::numeric_limits<std::size_t>::max());

}  // namespace bleedsim
