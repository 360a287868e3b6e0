#pragma once
// A user's text file read whole, with a message that says why it could not be.
#include <string>

namespace bleedsim {

// The bytes of `path`. Throws InputError naming the file: "cannot read <what> file: <reason>"
// (a folder, a missing file, no permission).
std::string read_text_file(const std::string& path, const std::string& what);

}  // namespace bleedsim
