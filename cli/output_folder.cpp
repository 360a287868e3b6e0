#include "cli/output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <string>
#include <system_error>

namespace bleedsim::cli {

namespace fs = std::filesystem;

namespace {

// The pid a running command wrote into its lock file; empty when it has not written it yet.
std::string pid_in(int fd) {
  char text[32] = {};
  const ssize_t n = pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, n > 0 ? std::size_t(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid;
}

// A limit of the file system that will hold `dir` (pathconf on its deepest folder that exists),
// or the POSIX one where it reports none.
long limit_for(const fs::path& dir, int name, long fallback) {
  std::error_code ec;
  fs::path existing = dir;
  while (!existing.empty() && !fs::is_directory(existing, ec)) existing = existing.parent_path();
  const long limit = pathconf(existing.empty() ? "." : existing.c_str(), name);
  return limit > 0 ? limit : fallback;
}

}  // namespace

void check_room_for_paths(const fs::path& dir, const std::string& longest_inside, const SourcePlace& where,
                          const std::string& key) {
  const long name_max = limit_for(dir, _PC_NAME_MAX, NAME_MAX);
  for (const fs::path& part : dir)
    if (long(part.string().size()) > name_max)
      throw InputError(where, key, "the folder name '" + part.string().substr(0, 40) + "...' is " +
                                       std::to_string(part.string().size()) + " characters long; a name may be at most " +
                                       std::to_string(name_max) + " (NAME_MAX)");
  // PATH_MAX counts the terminating NUL.
  const long path_max = limit_for(dir, _PC_PATH_MAX, PATH_MAX);
  const std::size_t longest = (dir / longest_inside).string().size();
  if (long(longest) >= path_max)
    throw InputError(where, key, "the output folder's path is " + std::to_string(dir.string().size()) +
                                     " characters long; with the longest path written in it ('" + longest_inside +
                                     "') it must be at most " +
                                     std::to_string(path_max - 1 - long(longest - dir.string().size())) + " (PATH_MAX " +
                                     std::to_string(path_max) + ")");
}

OutputFolder::OutputFolder(const fs::path& dir, const std::string& longest_inside, const SourcePlace& where,
                           const std::string& key)
    : dir_(dir), where_(where), key_(key) {
  if (dir.empty()) throw error("the output folder must not be empty");
  check_room_for_paths(dir, longest_inside, where, key);
  // A constructor that throws runs no destructor: what it made goes here.
  try {
    make(dir);
    lock();
  } catch (...) {
    remove_made();
    throw;
  }
}

OutputFolder::~OutputFolder() {
  if (lock_fd_ >= 0) {
    // Unlinked while still held: a command waiting on this file finds it gone and makes its own.
    std::error_code ignored;
    fs::remove(dir_ / kLockName, ignored);
    close(lock_fd_);
  }
  remove_made();
}

void OutputFolder::remove_made() {
  std::error_code ignored;
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) fs::remove(*it, ignored);
  created_.clear();
}

void OutputFolder::make(const fs::path& dir) {
  // Walk down from the deepest folder that exists, making each missing one and noting it.
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) missing.push_back(p);
  std::reverse(missing.begin(), missing.end());
  for (const fs::path& p : missing) {
    if (fs::create_directory(p, ec)) created_.push_back(p);
    else if (ec) throw error("cannot create output folder '" + p.string() + "': " + ec.message());
  }
  if (!fs::is_directory(dir, ec))
    throw error("cannot write to '" + dir.string() + "': it exists and is not a folder");
}

// flock(2) on a file in the folder: released by the kernel when the process ends however it ends,
// so a killed run never leaves a stale lock. The file may be unlinked by the holder as it releases
// it; a lock taken on an unlinked file holds nothing, so after locking, the file must still be the
// one at the path (else try again).
void OutputFolder::lock() {
  const fs::path path = dir_ / kLockName;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw error("cannot write to output folder '" + dir_.string() + "': " + std::strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int reason = errno;
      const std::string pid = pid_in(fd);
      close(fd);
      if (reason != EWOULDBLOCK)
        throw error("cannot lock output folder '" + dir_.string() + "': " + std::strerror(reason));
      throw error("output folder '" + dir_.string() + "' is in use by another bleedsim run" +
                  (pid.empty() ? std::string() : " (pid " + pid + ")") +
                  "; wait for it to end, or write to another folder");
    }
    struct stat held {}, named {};
    if (fstat(fd, &held) == 0 && stat(path.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      lock_fd_ = fd;
      // The pid is for the message another run prints; a full disk may keep it out, the lock holds.
      const std::string pid = std::to_string(getpid()) + "\n";
      const bool written = ftruncate(fd, 0) == 0 && pwrite(fd, pid.data(), pid.size(), 0) == ssize_t(pid.size());
      static_cast<void>(written);
      return;
    }
    close(fd);
  }
  throw error("cannot lock output folder '" + dir_.string() + "': its lock file keeps changing");
}

}  // namespace bleedsim::cli
