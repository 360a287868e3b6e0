#include "cli/output_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace bleedsim::cli {

namespace fs = std::filesystem;

namespace {

// In the swap folder: the last command's files moved aside, and the phase the swap is in.
constexpr const char* kOld = ".old";
constexpr const char* kJournal = ".journal";

// The journal's phases, each written (durably) before its first step. Every step of a phase can be
// repeated: a move is made only while its source is there, and renames are atomic.
constexpr const char* kAside = "aside";    // the last command's files (its manifest's names) go to .old
constexpr const char* kIn = "in";          // the new files (the swap folder's manifest's names) go in
constexpr const char* kFinish = "finish";  // the new manifest goes in, .old and the swap folder go
constexpr const char* kBack = "back";      // a failed swap is undone: the new files back, the old ones in

[[noreturn]] void fail(const std::string& what, const fs::path& path, const std::string& reason) {
  throw std::runtime_error("cannot " + what + " '" + path.string() + "': " + reason);
}

void check(const std::error_code& ec, const std::string& what, const fs::path& path) {
  if (ec) fail(what, path, ec.message());
}

// A test hook (docs/reliability.md): with BLEEDSIM_TEST_KILL_AT=N in its environment the process
// raises SIGKILL just before the Nth step that changes the folder in a swap or its recovery, so that
// a test can stop it at each one in turn.
void step() {
  static const long kill_at = [] {
    const char* at = std::getenv("BLEEDSIM_TEST_KILL_AT");
    return at ? std::atol(at) : 0L;
  }();
  static long steps = 0;
  if (++steps == kill_at) std::raise(SIGKILL);
}

bool present(const fs::path& path) {
  struct stat st {};
  if (lstat(path.c_str(), &st) == 0) return true;
  if (errno != ENOENT) fail("look at", path, std::strerror(errno));
  return false;
}

// A rename of our own bookkeeping (the journal, a manifest, the partial and swap folders).
void rename_ours(const fs::path& from, const fs::path& to) {
  step();
  if (std::rename(from.c_str(), to.c_str()) != 0)
    fail("move", from, std::string(std::strerror(errno)) + " (to '" + to.string() + "')");
}

// A move of an output file that never replaces what is at `to` (a user's file): renameat2's
// RENAME_NOREPLACE, or, where the file system cannot promise that (EINVAL: NFS), a look first.
void move(const fs::path& from, const fs::path& to) {
  step();
  int moved = renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE);
  if (moved != 0 && errno == EINVAL) {
    if (present(to)) errno = EEXIST;
    else moved = std::rename(from.c_str(), to.c_str());
  }
  if (moved != 0) fail("move", from, std::string(std::strerror(errno)) + " (to '" + to.string() + "')");
}

void remove_empty_folder(const fs::path& path) {
  step();
  std::error_code ec;
  fs::remove(path, ec);
  check(ec, "remove", path);
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

// `text` into `path` whole or not at all: written and flushed under a temporary name, renamed over.
void write_durably(const fs::path& path, const std::string& text) {
  const fs::path temporary = path.string() + ".tmp";
  const int fd = open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("write", temporary, std::strerror(errno));
  const bool written = write(fd, text.data(), text.size()) == ssize_t(text.size()) && fsync(fd) == 0;
  const int reason = errno;
  close(fd);
  if (!written) {
    std::error_code ignored;  // the failure being reported matters more than this one
    fs::remove(temporary, ignored);
    fail("write", temporary, std::strerror(reason));
  }
  rename_ours(temporary, path);
}

std::string read_text(const fs::path& path) {
  if (!present(path)) return "";
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) fail("read", path, std::strerror(errno));
  return text.str();
}

// A manifest's names; none where there is no manifest.
std::vector<std::string> names_in(const fs::path& manifest) {
  std::vector<std::string> names;
  std::istringstream lines(read_text(manifest));
  for (std::string name; std::getline(lines, name);)
    if (!name.empty()) names.push_back(name);
  return names;
}

// The swap of the files in `folder`: its paths and the steps of each phase.
class Swap {
 public:
  explicit Swap(const fs::path& folder)
      : folder_(folder), swap_(folder / OutputFiles::kSwap), old_(swap_ / kOld) {}

  // The partial folder, made durable with its manifest and journal, becomes the swap folder: from
  // here the new files are whole and go in, here or in the next command.
  void begin(const std::vector<std::string>& written) {
    const fs::path partial = folder_ / OutputFiles::kPartial;
    std::string manifest;
    for (const std::string& name : written) {
      sync(partial / name);
      manifest += name + "\n";
    }
    write_durably(partial / OutputFiles::kManifest, manifest);
    write_durably(partial / kJournal, kAside);
    sync(partial);
    rename_ours(partial, swap_);
    sync(folder_);
  }

  // Takes the swap on from the phase its journal names. A failure before the new files are all in
  // rolls it back, and throws.
  void complete() {
    const std::string phase = read_text(swap_ / kJournal);
    if (phase.empty()) return remove_empty_folder(swap_);  // killed after its last journal went
    if (phase == kBack) return roll_back();
    if (phase != kAside && phase != kIn && phase != kFinish)
      fail("read the swap's journal", swap_ / kJournal, "it names no phase ('" + phase + "'); bleedsim did not write it");
    try {
      if (phase == kAside) {
        move_old_aside();
        write_durably(swap_ / kJournal, kIn);
      }
      if (phase != kFinish) {
        move_new_in();
        write_durably(swap_ / kJournal, kFinish);
      }
    } catch (const std::exception& e) {
      roll_back_after(e);
    }
    finish();
  }

 private:
  void move_old_aside() {
    if (!present(old_)) {
      step();
      std::error_code ec;
      fs::create_directory(old_, ec);
      check(ec, "create", old_);
    }
    for (const std::string& name : names_in(folder_ / OutputFiles::kManifest))
      if (present(folder_ / name)) move(folder_ / name, old_ / name);
  }

  void move_new_in() {
    for (const std::string& name : names_in(swap_ / OutputFiles::kManifest))
      if (present(swap_ / name)) move(swap_ / name, folder_ / name);
  }

  void finish() {
    if (present(swap_ / OutputFiles::kManifest)) rename_ours(swap_ / OutputFiles::kManifest, folder_ / OutputFiles::kManifest);
    sync(folder_);
    step();
    std::error_code ec;
    fs::remove_all(old_, ec);
    check(ec, "remove", old_);
    step();
    fs::remove(swap_ / kJournal, ec);
    check(ec, "remove", swap_ / kJournal);
    remove_empty_folder(swap_);
  }

  // Each new file no longer in the swap folder was moved in (it is in the manifest because the swap
  // folder held it), so it goes back; each old one moved aside comes back. The swap folder is then
  // the partial folder again.
  void roll_back() {
    write_durably(swap_ / kJournal, kBack);
    for (const std::string& name : names_in(swap_ / OutputFiles::kManifest))
      if (!present(swap_ / name) && present(folder_ / name)) move(folder_ / name, swap_ / name);
    for (const std::string& name : names_in(folder_ / OutputFiles::kManifest))
      if (present(old_ / name)) move(old_ / name, folder_ / name);
    if (present(old_)) remove_empty_folder(old_);
    rename_ours(swap_, folder_ / OutputFiles::kPartial);
    sync(folder_);
  }

  [[noreturn]] void roll_back_after(const std::exception& failure) {
    const std::string partial = (folder_ / OutputFiles::kPartial).string();
    try {
      roll_back();
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string(failure.what()) + "; rolling the swap back failed too (" + e.what() +
                               "): it is left in " + swap_.string() + ", which the next run in the folder takes on");
    }
    throw std::runtime_error(std::string(failure.what()) + "; the swap was rolled back: the folder's last whole run "
                             "is as it was, the new files are in " + partial);
  }

  fs::path folder_, swap_, old_;
};

// A killed or failed command's files are cleared with a word, not silently: the user may have
// wanted its frames.
void say_what_is_cleared(const fs::path& partial) {
  if (!present(partial)) return;
  std::error_code ec;
  std::vector<std::string> left;
  for (fs::recursive_directory_iterator it(partial, ec), end; !ec && it != end; it.increment(ec))
    if (!it->is_directory(ec)) left.push_back(fs::relative(it->path(), partial, ec).string());
  if (left.empty()) return;
  std::sort(left.begin(), left.end());
  std::cerr << "bleedsim: note: clearing '" << partial.string() << "': " << left.size()
            << (left.size() == 1 ? " file" : " files") << " a killed or failed command left there (" << left.front()
            << (left.size() > 1 ? ", ..." : "") << "); copy them away before a run into this folder to keep them\n";
}

}  // namespace

std::string OutputFiles::longest_path(const std::vector<std::string>& paths) {
  // A file moved aside into .bleedsim-swap/.old/ (2 characters longer than .bleedsim-partial/) has
  // its whole name, shorter than its temporary name by a suffix of 4 or more: the longest path is
  // in the partial folder.
  std::string longest = (fs::path(kPartial) / kManifest).string() + ".tmp";
  for (const std::string& path : paths)
    if ((fs::path(kPartial) / path).string().size() > longest.size()) longest = (fs::path(kPartial) / path).string();
  return longest;
}

OutputFiles::OutputFiles(const OutputFolder& folder, std::vector<std::string> names)
    : folder_(folder.path()), names_(std::move(names)) {
  if (present(folder_ / kSwap)) Swap(folder_).complete();
  const std::vector<std::string> ours = names_in(folder_ / kManifest);
  for (const std::string& name : names_)
    if (present(folder_ / name) && std::find(ours.begin(), ours.end(), name) == ours.end())
      throw folder.error("'" + (folder_ / name).string() + "' was not written by a bleedsim run in this folder (its " +
                         kManifest + " does not list it); move it away, or write to another folder");
  const fs::path partial = folder_ / kPartial;
  say_what_is_cleared(partial);
  std::error_code ec;
  fs::remove_all(partial, ec);
  check(ec, "clear", partial);
  fs::create_directory(partial, ec);
  check(ec, "create", partial);
}

fs::path OutputFiles::partial(const std::string& name) const { return folder_ / kPartial / name; }

fs::path OutputFiles::published(const std::string& name) const { return folder_ / name; }

void OutputFiles::publish() {
  std::vector<std::string> written;
  for (const std::string& name : names_)
    if (present(partial(name))) written.push_back(name);
  Swap swap(folder_);
  swap.begin(written);
  swap.complete();
}

}  // namespace bleedsim::cli
