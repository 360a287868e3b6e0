#include "core/io/text_file.h"

#include <filesystem>
#include <sstream>

#include "core/runtime/input_file.h"
#include "core/runtime/memory.h"

namespace bleedsim {

std::ifstream open_text_file(const std::string& path, const std::string& what) {
  return open_input(InputFile{path, what + " file"});
}

std::string read_text_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
  std::ifstream in = open_text_file(path, what);
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > max_bytes)
    throw InputError(SourcePlace{path, 0, 0}, "",
                     "the " + what + " file is " + human_bytes(double(bytes)) + "; at most " +
                         human_bytes(double(max_bytes)) + " is read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace bleedsim
