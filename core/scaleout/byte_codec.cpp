#include "core/scaleout/byte_codec.h"

#include <cstring>

namespace bleedsim {

void ByteWriter::u32(std::uint32_t v) {
  for (int i = 0; i < 4; ++i) data_.push_back(std::uint8_t(v >> (8 * i)));
}

void ByteWriter::u64(std::uint64_t v) {
  for (int i = 0; i < 8; ++i) data_.push_back(std::uint8_t(v >> (8 * i)));
}

void ByteWriter::f64(double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  u64(bits);
}

void ByteWriter::raw(const void* data, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  data_.insert(data_.end(), p, p + size);
}

void ByteWriter::bytes(const std::vector<std::uint8_t>& v) {
  u64(v.size());
  raw(v.data(), v.size());
}

void ByteWriter::text(const std::string& v) {
  u64(v.size());
  raw(v.data(), v.size());
}

const std::uint8_t* ByteReader::take(std::size_t size, const std::string& what) {
  if (size > remaining())
    throw TruncatedBytes(what + " is cut off: " + std::to_string(size) + " bytes needed at byte " + std::to_string(at_) +
                         ", " + std::to_string(remaining()) + " left");
  const std::uint8_t* p = data_ + at_;
  at_ += size;
  return p;
}

std::uint32_t ByteReader::u32(const std::string& what) {
  const std::uint8_t* p = take(4, what);
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t(p[i]) << (8 * i);
  return v;
}

std::uint64_t ByteReader::u64(const std::string& what) {
  const std::uint8_t* p = take(8, what);
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= std::uint64_t(p[i]) << (8 * i);
  return v;
}

double ByteReader::f64(const std::string& what) {
  const std::uint64_t bits = u64(what);
  double v = 0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

void ByteReader::raw(void* out, std::size_t size, const std::string& what) {
  const std::uint8_t* p = take(size, what);
  if (size) std::memcpy(out, p, size);
}

// A length read before the bytes it counts, checked against what is left before anything is
// allocated for them.
std::size_t ByteReader::length(const std::string& what) {
  const std::uint64_t n = u64(what + "'s length");
  if (n > remaining())
    throw TruncatedBytes(what + " says it is " + std::to_string(n) + " bytes long at byte " + std::to_string(at_) +
                         ", but only " + std::to_string(remaining()) + " are left");
  return std::size_t(n);
}

std::size_t ByteReader::count(const std::string& what, std::size_t least_bytes) {
  const std::uint64_t n = u64(what);
  if (n > remaining() / least_bytes)
    throw TruncatedBytes(what + " is " + std::to_string(n) + " at byte " + std::to_string(at_) + ", but the " +
                         std::to_string(remaining()) + " bytes left hold at most " +
                         std::to_string(remaining() / least_bytes));
  return std::size_t(n);
}

std::vector<std::uint8_t> ByteReader::bytes(const std::string& what) {
  const std::size_t n = length(what);
  const std::uint8_t* p = take(n, what);
  return std::vector<std::uint8_t>(p, p + n);
}

std::string ByteReader::text(const std::string& what) {
  const std::size_t n = length(what);
  const std::uint8_t* p = take(n, what);
  return std::string(reinterpret_cast<const char*>(p), n);
}

}  // namespace bleedsim
