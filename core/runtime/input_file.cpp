#include "core/runtime/input_file.h"

#include <filesystem>

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

// What a file that is not a regular one is, in words.
std::string kind_of(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::fifo: return "a named pipe";
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::socket: return "a socket";
    default: return "a file of an unknown kind";
  }
}

}  // namespace

InputError unreadable(const InputFile& file, const std::string& why) {
  if (file.key.empty()) return InputError(SourcePlace{file.path, 0, 0}, "", "cannot read " + file.what + ": " + why);
  return InputError(file.where, file.key, "cannot read " + file.what + " '" + file.path + "': " + why);
}

void require_regular_file(const InputFile& file) {
  if (file.path.empty()) {
    if (file.key.empty()) throw unreadable(file, "its path is empty");
    throw InputError(file.where, file.key, "is empty; it names the " + file.what + " to read");
  }
  std::error_code error;
  const fs::file_status status = fs::status(file.path, error);
  if (error) throw unreadable(file, error.message());
  if (status.type() == fs::file_type::regular) return;
  throw unreadable(file, "it is " + kind_of(status.type()) + ", not a regular file");
}

}  // namespace bleedsim
