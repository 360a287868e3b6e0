// The tissue PNG loader (core/io/tissue_png.h) on any bytes: the header check, stb's decoder and
// the bilinear resampling to a 17 x 13 panel. It must refuse them with an InputError or give the
// panel's image, never crash or read out of bounds; a texture whose decoding would take more than
// 64 MiB must be refused before it is decoded.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/io/tissue_png.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const bleedsim::Image image = bleedsim::decode_tissue_png(
        bytes, {"fuzzed.png", "texture", "tissue.texture", {"fuzzed.toml", 1, 1}}, 17, 13, std::size_t{64} << 20);
    if (image.width != 17 || image.height != 13 || image.rgba.size() != 17u * 13u * 4u) std::abort();
  } catch (const bleedsim::InputError&) {
  }
  return 0;
}
