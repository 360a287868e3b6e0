#include "cli/output_folder.h"

#include <algorithm>
#include <system_error>

namespace bleedsim::cli {

namespace fs = std::filesystem;

OutputFolder::OutputFolder(const fs::path& dir, const SourcePlace& where, const std::string& key)
    : dir_(dir), where_(where), key_(key) {
  if (dir.empty()) throw error("the output folder must not be empty");
  make(dir);
}

OutputFolder::~OutputFolder() {
  std::error_code ignored;
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) fs::remove(*it, ignored);
}

fs::path OutputFolder::subfolder(const std::string& name) {
  make(dir_ / name);
  return dir_ / name;
}

void OutputFolder::make(const fs::path& dir) {
  // Walk down from the deepest folder that exists, making each missing one and noting it.
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) missing.push_back(p);
  std::reverse(missing.begin(), missing.end());
  for (const fs::path& p : missing) {
    if (!fs::create_directory(p, ec) && ec)
      throw error("cannot create output folder '" + p.string() + "': " + ec.message());
    created_.push_back(p);
  }
  if (!fs::is_directory(dir, ec))
    throw error("cannot write to '" + dir.string() + "': it exists and is not a folder");
}

}  // namespace bleedsim::cli
