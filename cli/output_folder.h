#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "core/runtime/input_error.h"

namespace bleedsim::cli {

// The output folder of one command (docs/reliability.md). Made (with its parents) only after
// everything else about the input has been checked, and then held: one run at a time writes into
// a folder. The lock is taken before anything in the folder is opened, and another run that asks
// for the folder is refused, naming it and the pid that holds it. If the command then stops on bad
// input before keep(), the folders it made go again, so bad input leaves nothing behind.
class OutputFolder {
 public:
  // The lock file, beside the outputs; it holds the running command's pid.
  static constexpr const char* kLockName = ".bleedsim.lock";

  // Throws InputError at `where`/`key` when the folder cannot be made or written, or is in use, or
  // its path leaves no room for `longest_inside` (see check_room_for_paths), before anything is made.
  OutputFolder(const std::filesystem::path& dir, const std::string& longest_inside, const SourcePlace& where,
               const std::string& key);
  // Releases the lock (and removes its file); removes the folders made, when not kept.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return dir_; }
  // The command has started writing: keep what was made.
  void keep() { created_.clear(); }
  // An error about this folder at the place it was named.
  InputError error(const std::string& message) const { return InputError(where_, key_, message); }

 private:
  void make(const std::filesystem::path& dir);
  void lock();
  void remove_made();

  std::filesystem::path dir_;
  SourcePlace where_;
  std::string key_;
  std::vector<std::filesystem::path> created_;  // outermost first
  int lock_fd_ = -1;
};

// Refuses, with InputError at `where`/`key` naming the limit, an output folder whose path leaves no
// room for `longest_inside`, the longest path (relative to the folder) the command makes in it:
// the whole path must fit in PATH_MAX and each of the folder's names in NAME_MAX. Checked before
// anything is made, so a run cannot fail half way with "File name too long" and strand its files.
void check_room_for_paths(const std::filesystem::path& dir, const std::string& longest_inside, const SourcePlace& where,
                          const std::string& key);

}  // namespace bleedsim::cli
