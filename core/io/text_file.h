#pragma once
// A user's text file, opened or read whole, with a message that says why it could not be.
#include <cstdint>
#include <fstream>
#include <string>

namespace bleedsim {

// `path` opened for reading. Throws InputError naming the file, "cannot read <what> file '<path>':
// <reason>", for anything but a regular file (a missing one, a directory, a named pipe: refused
// unopened) and one it cannot open (no permission).
std::ifstream open_text_file(const std::string& path, const std::string& what);

// The bytes of `path`, with the same errors, refused before it is read when it holds more than
// `max_bytes`.
std::string read_text_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

}  // namespace bleedsim
