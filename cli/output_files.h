#pragma once
// The files one command (a run, a study) writes into its output folder (docs/reliability.md, "A
// folder shows one whole run"). They are written into a partial folder beside the last command's,
// and when the command ends they are swapped in together, by a journaled swap whose every state the
// next command in the folder recognises and completes or rolls back: the folder shows one whole
// command's files, never a mix of two, never none. Only what the last command wrote, as its manifest
// lists, is ever replaced; a file of the user's is never moved or deleted.
#include <filesystem>
#include <string>
#include <vector>

#include "cli/output_folder.h"

namespace bleedsim::cli {

class OutputFiles {
 public:
  // Where the running (or a failed, or a killed) command's files are.
  static constexpr const char* kPartial = ".bleedsim-partial";
  // A swap under way: the new files, the last command's moved aside (.old) and the journal.
  static constexpr const char* kSwap = ".bleedsim-swap";
  // The names, one a line, of the files at the top of the folder that the last command wrote.
  static constexpr const char* kManifest = ".bleedsim-manifest";

  // The longest path, relative to the folder, that a command makes in it, given `paths`: those it
  // writes, relative to the partial folder, under their temporary names.
  static std::string longest_path(const std::vector<std::string>& paths);

  // In `folder`, whose lock this command holds: completes a swap a killed command left (or rolls it
  // back, throwing std::runtime_error with why); refuses, with the folder's InputError, a name of
  // `names` (what this command may write, by name in the folder) that is there and not the last
  // command's; then clears what a killed or failed command left in the partial folder and makes that
  // folder again, empty. Throws std::runtime_error, naming the path and the OS error, when the file
  // system fails.
  OutputFiles(const OutputFolder& folder, std::vector<std::string> names);

  // Where this command writes `name` (one of its names) while it runs, and where it is once published.
  std::filesystem::path partial(const std::string& name) const;
  std::filesystem::path published(const std::string& name) const;
  // Swaps the command's files in for the last command's, together. Once the partial folder, made
  // durable with its manifest, is renamed to the swap folder, the swap completes, here or, after a
  // kill, in the next command. A step that fails rolls it back and throws std::runtime_error naming
  // the file and the OS error: the folder shows the last command's files as they were, this one's
  // are in the partial folder.
  void publish();

 private:
  std::filesystem::path folder_;
  std::vector<std::string> names_;
};

}  // namespace bleedsim::cli
