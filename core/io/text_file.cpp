#include "core/io/text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/runtime/input_error.h"

namespace bleedsim {

std::string read_text_file(const std::string& path, const std::string& what) {
  const SourcePlace file{path, 0, 0};
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(file, "", "cannot read " + what + " file: it is a folder");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot read " + what + " file: " + std::strerror(errno ? errno : ENOENT));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace bleedsim
