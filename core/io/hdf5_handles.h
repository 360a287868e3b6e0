#pragma once
// What every HDF5 file bleedsim writes shares: handles that close themselves, errors as exceptions
// that name the file and the OS error, and the library set up so that a failed write cannot crash
// the process at exit.
#include <hdf5.h>

#include <string>
#include <utility>

namespace bleedsim {

// Owns one HDF5 identifier and closes it with the function that matches its kind. close() reports
// the status (a writer must know the file really closed); the destructor cannot, and ignores it.
template <herr_t (*Close)(hid_t)>
class Hdf5Handle {
 public:
  Hdf5Handle() = default;
  explicit Hdf5Handle(hid_t id) : id_(id) {}
  Hdf5Handle(Hdf5Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)) {}
  Hdf5Handle& operator=(Hdf5Handle&& other) noexcept {
    if (this != &other) {
      close();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
    }
    return *this;
  }
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  ~Hdf5Handle() { close(); }

  hid_t get() const { return id_; }
  herr_t close() { return id_ >= 0 ? Close(std::exchange(id_, H5I_INVALID_HID)) : 0; }

 private:
  hid_t id_ = H5I_INVALID_HID;
};

// Throws std::runtime_error: `what`, then why HDF5 failed, from its error stack: the OS error when
// a frame of the stack records one, else where the failure was first detected. One line either way.
[[noreturn]] void throw_hdf5_error(const std::string& what);

// Every HDF5 call goes through one of these: a negative id or status becomes an exception that
// names the file and the operation.
struct Hdf5Checker {
  std::string file;

  hid_t operator()(hid_t id, const std::string& operation) const {
    if (id < 0) fail(operation);
    return id;
  }
  void operator()(herr_t status, const std::string& operation) const {
    if (status < 0) fail(operation);
  }
  [[noreturn]] void fail(const std::string& operation) const;
};

// Call before a writer's first HDF5 call. HDF5 1.10 crashes at exit (in H5_term_library) closing a
// file whose last write or close failed (a full disk, a file size limit): its exit handler is turned
// off, so a failed write ends in the writer's message and exit code, and the writers close every
// file they open themselves. HDF5's own printing of errors to stderr is turned off too: errors come
// back as exceptions carrying its message.
void prepare_hdf5_for_writing();

}  // namespace bleedsim
