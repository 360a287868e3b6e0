#include "core/io/whole_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace bleedsim {
namespace {

// Every byte written, then flushed to disk and closed, each step checked: a full disk (ENOSPC) or
// a file size limit (EFBIG) must not leave a short file that looks written. Returns 0, or the
// errno of the step that failed.
int write_and_sync(const std::string& path, const char* bytes, std::size_t size) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = write(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int reason = errno;
      close(fd);
      return reason;
    }
    done += std::size_t(n);
  }
  const int synced = fsync(fd) == 0 ? 0 : errno;
  const int closed = close(fd) == 0 ? 0 : errno;
  return synced ? synced : closed;
}

}  // namespace

void write_whole_file(const std::string& path, const void* data, std::size_t size, const std::string& what) {
  const std::string temporary = path + ".tmp";
  if (const int reason = write_and_sync(temporary, static_cast<const char*>(data), size)) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write " + what + " '" + path + "': " + std::strerror(reason));
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write " + what + " '" + path + "': " + error.message());
  }
}

}  // namespace bleedsim
