#include "core/runtime/input_file.h"

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/runtime/hash.h"

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

std::ifstream open_input(const InputFile& file) {
  require_regular_file(file);
  errno = 0;
  std::ifstream in(file.path, std::ios::binary);
  if (!in) throw unreadable(file, std::strerror(errno ? errno : EIO));
  return in;
}

std::uint64_t hash_of_file(const InputFile& file) {
  std::ifstream in = open_input(file);
  std::uint64_t hash = fnv1a64(nullptr, 0);
  std::array<char, 1 << 16> piece;
  while (in.read(piece.data(), piece.size()) || in.gcount() > 0)
    hash = fnv1a64(piece.data(), std::size_t(in.gcount()), hash);
  if (in.bad()) throw unreadable(file, std::strerror(errno ? errno : EIO));
  return hash;
}

}  // namespace bleedsim
