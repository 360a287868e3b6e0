#include "cli/run_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace bleedsim::cli {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& what, const fs::path& path, const std::string& reason) {
  throw std::runtime_error("cannot " + what + " '" + path.string() + "': " + reason);
}

void check(const std::error_code& ec, const std::string& what, const fs::path& path) {
  if (ec) fail(what, path, ec.message());
}

void move(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) fail("move", from, ec.message() + " (to '" + to.string() + "')");
}

bool present(const fs::path& path) {
  struct stat st {};
  if (lstat(path.c_str(), &st) == 0) return true;
  if (errno != ENOENT) fail("look at", path, std::strerror(errno));
  return false;
}

// Data and names on disk, not only in the page cache: a renamed file must not come back empty
// after a power cut.
void sync(const fs::path& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("open", path, std::strerror(errno));
  const int synced = fsync(fd);
  const int reason = errno;
  close(fd);
  if (synced != 0 && reason != EINVAL) fail("flush", path, std::strerror(reason));  // EINVAL: cannot sync this kind
}

// Completes a swap from wherever it stopped; every step can be repeated. The last run's files are
// moved aside (into .replacing, renamed .replaced once all are there), then the new run's are
// moved in, then the old ones deleted.
void finish_swap(const fs::path& folder) {
  const fs::path swap = folder / RunFiles::kSwap;
  const fs::path moving = swap / ".replacing", replaced = swap / ".replaced";
  if (!present(replaced)) {
    std::error_code ec;
    fs::create_directory(moving, ec);
    check(ec, "create", moving);
    for (const std::string& name : RunFiles::names())
      if (present(folder / name)) move(folder / name, moving / name);
    move(moving, replaced);
  }
  for (const std::string& name : RunFiles::names())
    if (present(swap / name)) move(swap / name, folder / name);
  sync(folder);
  std::error_code ec;
  fs::remove_all(replaced, ec);
  check(ec, "remove", replaced);
  fs::remove(swap, ec);
  check(ec, "remove", swap);
}

}  // namespace

const std::vector<std::string>& RunFiles::names() {
  static const std::vector<std::string> names = {"frames.h5", "png", "contact_sheet.png", "view_contact_sheet.png"};
  return names;
}

const std::string& RunFiles::longest_path() {
  // A file in the partial folder under its temporary name (NAME.partial for frames.h5, NAME.tmp for
  // a PNG: the longer is counted), or the last run's moved aside in a swap; in png/, a frame's PNG
  // (png_name in cli/frame_output.cpp).
  static const std::string longest = [] {
    std::vector<std::string> names = RunFiles::names();
    names.push_back("png/view_000000.png");
    std::string longest;
    for (const std::string& name : names)
      for (const fs::path& path : {fs::path(kSwap) / ".replacing" / name, fs::path(kPartial) / (name + ".partial")})
        if (path.string().size() > longest.size()) longest = path.string();
    return longest;
  }();
  return longest;
}

RunFiles::RunFiles(const fs::path& folder) : folder_(folder) {
  if (present(folder / kSwap)) finish_swap(folder);
  const fs::path partial = folder / kPartial;
  std::error_code ec;
  fs::remove_all(partial, ec);
  check(ec, "clear", partial);
  fs::create_directory(partial, ec);
  check(ec, "create", partial);
}

fs::path RunFiles::partial(const std::string& name) const { return folder_ / kPartial / name; }

fs::path RunFiles::published(const std::string& name) const { return folder_ / name; }

void RunFiles::publish() {
  const fs::path partial = folder_ / kPartial;
  for (const std::string& name : names())
    if (present(partial / name)) sync(partial / name);
  sync(partial);
  move(partial, folder_ / kSwap);  // the run is whole from here: the next run completes the swap
  sync(folder_);
  finish_swap(folder_);
}

}  // namespace bleedsim::cli
