#pragma once
// The files of one run in its output folder (docs/reliability.md): frames.h5, png/,
// contact_sheet.png and, with a [view], view_contact_sheet.png. A run writes them into a partial folder beside the last run's, and when it
// ends they are swapped in together, so the folder shows one whole run, never a mix of two.
#include <filesystem>
#include <string>
#include <vector>

namespace bleedsim::cli {

class RunFiles {
 public:
  // What a run writes, by name in the folder.
  static const std::vector<std::string>& names();
  // The longest path, relative to the folder, a run makes in it (its folder must leave room for it).
  static const std::string& longest_path();
  // Where the running (or a failed, or a killed) run's files are.
  static constexpr const char* kPartial = ".bleedsim-partial";
  // A swap under way: the run's files, then the last run's, moved aside.
  static constexpr const char* kSwap = ".bleedsim-swap";

  // In a folder whose lock this run holds: finishes a swap a killed run left half done, clears
  // what a killed or failed run left in the partial folder, and makes that folder again, empty.
  // Throws std::runtime_error, naming the path and the OS error, when the filesystem fails.
  explicit RunFiles(const std::filesystem::path& folder);

  // Where this run writes `name` (one of names()) while it runs, and where it is once published.
  std::filesystem::path partial(const std::string& name) const;
  std::filesystem::path published(const std::string& name) const;
  // Swaps the run's files in for the last run's, together: first this run's are made durable and
  // its partial folder renamed to the swap folder in one step; from then on the swap completes,
  // here or, after a crash, in the next run.
  void publish();

 private:
  std::filesystem::path folder_;
};

}  // namespace bleedsim::cli
