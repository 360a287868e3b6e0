#include "core/io/hdf5_handles.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace bleedsim {
namespace {

// Why HDF5 failed: the OS error when a frame of the stack records one (its file drivers write
// "errno = 28, error message = ..."), else the innermost frame's description. HDF5's descriptions
// can hold a newline (a ctime() timestamp), and a failure is reported in one line.
struct Reason {
  std::string innermost;
  int os_error = 0;
};

herr_t read_frame(unsigned depth, const H5E_error2_t* error, void* out) {
  Reason& reason = *static_cast<Reason*>(out);
  if (!error->desc) return 0;
  const std::string desc = error->desc;
  if (depth == 0) reason.innermost = desc;
  const std::size_t at = desc.find("errno = ");
  if (at != std::string::npos && reason.os_error == 0) reason.os_error = std::atoi(desc.c_str() + at + 8);
  return 0;
}

}  // namespace

void throw_hdf5_error(const std::string& what) {
  Reason reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, read_frame, &reason);
  if (reason.os_error > 0) throw std::runtime_error(what + ": " + std::strerror(reason.os_error));
  std::string detail = reason.innermost;
  for (char& c : detail)
    if (c == '\n' || c == '\r') c = ' ';
  throw std::runtime_error(what + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}

void Hdf5Checker::fail(const std::string& operation) const {
  throw_hdf5_error("cannot " + operation + " in HDF5 file '" + file + "'");
}

void prepare_hdf5_for_writing() {
  H5dont_atexit();  // takes effect only before the library's first call in the process
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

}  // namespace bleedsim
