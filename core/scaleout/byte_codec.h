#pragma once
// Little-endian numbers, strings and byte strings in a byte buffer: the shard files and the
// messages between ranks. Fixed widths and byte order, so a file written on one machine reads on
// any other. The reader checks every length against what is left before it allocates, so a cut or
// damaged buffer is refused with what was being read, never read past.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace bleedsim {

class ByteWriter {
 public:
  void u32(std::uint32_t v);
  void u64(std::uint64_t v);
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v);
  void raw(const void* data, std::size_t size);
  // A length (u64), then the bytes.
  void bytes(const std::vector<std::uint8_t>& v);
  void text(const std::string& v);

  const std::vector<std::uint8_t>& data() const { return data_; }
  std::vector<std::uint8_t> take() { return std::move(data_); }

 private:
  std::vector<std::uint8_t> data_;
};

// What a ByteReader throws: the buffer ends before, or holds a length longer than, what is read.
class TruncatedBytes : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  // `what` names the field in the error ("job 3's host").
  std::uint32_t u32(const std::string& what);
  std::uint64_t u64(const std::string& what);
  std::int32_t i32(const std::string& what) { return static_cast<std::int32_t>(u32(what)); }
  double f64(const std::string& what);
  void raw(void* out, std::size_t size, const std::string& what);
  std::vector<std::uint8_t> bytes(const std::string& what);
  std::string text(const std::string& what);
  // A count (u64) of things that take at least `least_bytes` each, checked against what is left
  // before anything is allocated for them.
  std::size_t count(const std::string& what, std::size_t least_bytes);

  std::size_t offset() const { return at_; }
  std::size_t remaining() const { return size_ - at_; }

 private:
  const std::uint8_t* take(std::size_t size, const std::string& what);
  std::size_t length(const std::string& what);

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

}  // namespace bleedsim
