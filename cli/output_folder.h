#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "core/runtime/input_error.h"

namespace bleedsim::cli {

// The run's output folder. Made (with its parents) only after everything else about the run has
// been checked; if the run then stops on bad input before keep(), the folders it made go again,
// so bad input leaves nothing behind.
class OutputFolder {
 public:
  // Throws InputError at `where`/`key` when the folder cannot be made or written.
  OutputFolder(const std::filesystem::path& dir, const SourcePlace& where, const std::string& key);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return dir_; }
  // A subfolder (made now), e.g. "png".
  std::filesystem::path subfolder(const std::string& name);
  // The run has started writing: keep what was made.
  void keep() { created_.clear(); }
  // An error about this folder at the place it was named.
  InputError error(const std::string& message) const { return InputError(where_, key_, message); }

 private:
  void make(const std::filesystem::path& dir);

  std::filesystem::path dir_;
  SourcePlace where_;
  std::string key_;
  std::vector<std::filesystem::path> created_;  // outermost first
};

}  // namespace bleedsim::cli
