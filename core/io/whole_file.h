#pragma once
#include <cstddef>
#include <string>

namespace bleedsim {

// Writes `size` bytes to `path` through a temporary file (`path`.tmp) renamed into place, so a
// reader never sees half a file, every write checked and flushed to disk. Throws
// std::runtime_error "cannot write <what> '<path>': <OS error>" (a full disk, a file size limit)
// when it cannot, leaving no temporary file.
void write_whole_file(const std::string& path, const void* data, std::size_t size, const std::string& what);

}  // namespace bleedsim
