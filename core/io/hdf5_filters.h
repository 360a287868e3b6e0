#pragma once
// HDF5's shuffle and deflate filters, run outside the library (issue 17): a run filters its frames'
// chunks on worker threads and hands HDF5 the finished bytes (H5Dwrite_chunk), since HDF5 itself runs
// its filters on the one thread that writes. The bytes are those HDF5's own filters store for the
// same chunk (H5Zshuffle.c and H5Zdeflate.c), with the same zlib: a reader decodes them through the
// pipeline the dataset declares, as it would any chunk HDF5 wrote.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bleedsim {

// The chunk HDF5 stores for `bytes` bytes of `element_size`-byte elements through the pipeline
// H5Pset_shuffle + H5Pset_deflate(level) declare, level 1-9, into `chunk` (overwritten, its
// capacity kept). `bytes` is a whole number of elements. Safe from several threads at once.
void shuffle_then_deflate(const std::uint8_t* data, std::size_t bytes, std::size_t element_size, int level,
                          std::vector<std::uint8_t>& chunk);

}  // namespace bleedsim
