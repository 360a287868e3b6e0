#include "core/io/hdf5_filters.h"

#include <zlib.h>

#include <stdexcept>
#include <string>

namespace bleedsim {
namespace {

// H5Z__filter_shuffle: byte i of element j goes to i * elements + j, so the chunk holds every
// element's first byte, then every second byte, and so on. HDF5 skips 1-byte elements and a chunk
// of one element, which this order leaves as they are anyway; a trailing part-element (HDF5 copies
// it last) cannot occur in a chunk of whole elements.
void shuffle(const std::uint8_t* data, std::size_t bytes, std::size_t element_size, std::vector<std::uint8_t>& out) {
  const std::size_t elements = bytes / element_size;
  out.resize(bytes);
  for (std::size_t i = 0; i < element_size; ++i) {
    std::uint8_t* to = out.data() + i * elements;
    const std::uint8_t* from = data + i;
    for (std::size_t j = 0; j < elements; ++j, from += element_size) to[j] = *from;
  }
}

}  // namespace

void shuffle_then_deflate(const std::uint8_t* data, std::size_t bytes, std::size_t element_size, int level,
                          std::vector<std::uint8_t>& chunk) {
  if (element_size == 0 || bytes % element_size != 0 || level < 1 || level > 9)
    throw std::logic_error("shuffle_then_deflate: " + std::to_string(bytes) + " bytes of " +
                           std::to_string(element_size) + "-byte elements at level " + std::to_string(level));
  // The shuffled bytes: one buffer per thread, kept, as large as the largest chunk it has shuffled.
  thread_local std::vector<std::uint8_t> shuffled;
  const std::uint8_t* source = data;
  if (element_size > 1) {
    shuffle(data, bytes, element_size, shuffled);
    source = shuffled.data();
  }
  // H5Z__filter_deflate: compress2 at the level, into ceil(1.001 n) + 12 bytes, never fewer than
  // zlib's compressBound(n), so it never runs out of room: a chunk is always deflated (filter mask
  // 0), even incompressible bytes, which come out a little larger than they went in.
  uLongf size = compressBound(uLong(bytes));
  chunk.resize(size);
  const int status = compress2(chunk.data(), &size, source, uLong(bytes), level);
  if (status != Z_OK)
    throw std::runtime_error("deflate failed (zlib status " + std::to_string(status) + ") on a chunk of " +
                             std::to_string(bytes) + " bytes");
  chunk.resize(size);
}

}  // namespace bleedsim
