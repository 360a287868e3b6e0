// A job record's bytes: the magic, the version, then two sections, each its length (u64) and its
// fields in the order of JobRecord: the data, then the run (the job's index, where it ran, its
// timing). Integers little-endian, floats as their IEEE
// bits, a string or a vector as its count (u64) and its elements.
#include "core/study/job_record.h"

#include <cstring>
#include <stdexcept>

namespace bleedsim {
namespace {

class Writer {
 public:
  std::vector<std::uint8_t> bytes;

  void unsigned_le(std::uint64_t v, int size) {
    for (int i = 0; i < size; ++i) bytes.push_back(std::uint8_t(v >> (8 * i)));
  }
  void u32(std::uint32_t v) { unsigned_le(v, 4); }
  void u64(std::uint64_t v) { unsigned_le(v, 8); }
  void i32(std::int32_t v) { unsigned_le(std::uint32_t(v), 4); }
  void f32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    u32(bits);
  }
  void f64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, 8);
    u64(bits);
  }
  void text(const std::string& s) {
    u64(s.size());
    bytes.insert(bytes.end(), s.begin(), s.end());
  }
  template <class T, class Put>
  void list(const std::vector<T>& values, Put put) {
    u64(values.size());
    for (const T& v : values) (this->*put)(v);
  }
  void section(const Writer& inner) {
    u64(inner.bytes.size());
    bytes.insert(bytes.end(), inner.bytes.begin(), inner.bytes.end());
  }
};

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size, std::size_t offset) : data_(data), size_(size), at_(offset) {}

  std::uint64_t unsigned_le(int size, const char* what) {
    need(std::size_t(size), what);
    std::uint64_t v = 0;
    for (int i = 0; i < size; ++i) v |= std::uint64_t(data_[at_ + std::size_t(i)]) << (8 * i);
    at_ += std::size_t(size);
    return v;
  }
  std::uint32_t u32(const char* what) { return std::uint32_t(unsigned_le(4, what)); }
  std::uint64_t u64(const char* what) { return unsigned_le(8, what); }
  std::int32_t i32(const char* what) { return std::int32_t(u32(what)); }
  float f32(const char* what) {
    const std::uint32_t bits = u32(what);
    float v;
    std::memcpy(&v, &bits, 4);
    return v;
  }
  double f64(const char* what) {
    const std::uint64_t bits = u64(what);
    double v;
    std::memcpy(&v, &bits, 8);
    return v;
  }
  std::string text(const char* what) {
    const std::uint64_t n = count(1, what);
    std::string s(reinterpret_cast<const char*>(data_ + at_), std::size_t(n));
    at_ += std::size_t(n);
    return s;
  }
  template <class T, class Get>
  std::vector<T> list(Get get, std::size_t element_size, const char* what) {
    const std::uint64_t n = count(element_size, what);
    std::vector<T> values;
    values.reserve(std::size_t(n));
    for (std::uint64_t i = 0; i < n; ++i) values.push_back((this->*get)(what));
    return values;
  }
  // A section's reader: its length read, the outer reader moved past it.
  Reader section(const char* what) {
    const std::uint64_t n = count(1, what);
    Reader inner(data_, at_ + std::size_t(n), at_);
    at_ += std::size_t(n);
    return inner;
  }
  void expect_end(const char* what) const {
    if (at_ != size_)
      throw std::runtime_error(std::string("job record: ") + std::to_string(size_ - at_) + " bytes left over after the " +
                               what);
  }

 private:
  // A count of elements of `size` bytes that the bytes left can hold (garbage cannot ask for more).
  std::uint64_t count(std::size_t size, const char* what) {
    const std::uint64_t n = u64(what);
    if (n > (size_ - at_) / size)
      throw std::runtime_error(std::string("job record: truncated: ") + what + " says " + std::to_string(n) +
                               " elements, and " + std::to_string(size_ - at_) + " bytes are left");
    return n;
  }
  void need(std::size_t n, const char* what) const {
    if (size_ - at_ < n)
      throw std::runtime_error(std::string("job record: truncated at byte ") + std::to_string(at_) + " reading " + what);
  }

  const std::uint8_t* data_;
  std::size_t size_, at_;
};

Writer data_section(const JobRecord& r) {
  Writer w;
  w.u64(r.study_key);
  w.u32(r.setting);
  w.u32(r.seed_index);
  w.u64(r.seed);
  w.text(r.status);
  for (const std::vector<double>* series : {&r.front_mm, &r.covered_area_mm2, &r.volume_mm3, &r.pile_height_mm, &r.fastest_mm_s})
    w.list(*series, &Writer::f64);
  w.i32(r.grid_width);
  w.i32(r.grid_height);
  w.list(r.snapshot_frames, &Writer::i32);
  for (const std::vector<float>* field : {&r.film_mm, &r.stain, &r.rgb}) w.list(*field, &Writer::f32);
  return w;
}

}  // namespace

std::vector<std::uint8_t> data_bytes(const JobRecord& record) { return data_section(record).bytes; }

std::vector<std::uint8_t> serialize(const JobRecord& r) {
  Writer timing;
  timing.u32(r.job);
  timing.u32(std::uint32_t(r.backend));
  timing.text(r.device);
  timing.list(r.frame_seconds, &Writer::f64);
  Writer w;
  w.bytes.assign(kJobRecordMagic, kJobRecordMagic + sizeof kJobRecordMagic);
  w.u32(kJobRecordVersion);
  w.section(data_section(r));
  w.section(timing);
  return w.bytes;
}

JobRecord deserialize(const std::vector<std::uint8_t>& bytes) {
  if (bytes.size() < sizeof kJobRecordMagic || std::memcmp(bytes.data(), kJobRecordMagic, sizeof kJobRecordMagic) != 0)
    throw std::runtime_error("job record: not a bleedsim study job record (no BSJOBREC at its start)");
  Reader in(bytes.data(), bytes.size(), sizeof kJobRecordMagic);
  const std::uint32_t version = in.u32("the version");
  if (version != kJobRecordVersion)
    throw std::runtime_error("job record: version " + std::to_string(version) + "; this bleedsim reads version " +
                             std::to_string(kJobRecordVersion));
  JobRecord r;
  Reader data = in.section("the data section");
  r.study_key = data.u64("the study key");
  r.setting = data.u32("the setting");
  r.seed_index = data.u32("the seed index");
  r.seed = data.u64("the seed");
  r.status = data.text("the status");
  for (std::vector<double>* series : {&r.front_mm, &r.covered_area_mm2, &r.volume_mm3, &r.pile_height_mm, &r.fastest_mm_s})
    *series = data.list<double>(&Reader::f64, 8, "a per-frame measure");
  r.grid_width = data.i32("the grid width");
  r.grid_height = data.i32("the grid height");
  r.snapshot_frames = data.list<std::int32_t>(&Reader::i32, 4, "the snapshot frames");
  for (std::vector<float>* field : {&r.film_mm, &r.stain, &r.rgb}) *field = data.list<float>(&Reader::f32, 4, "a snapshot field");
  data.expect_end("data section");
  Reader timing = in.section("the run section");
  r.job = timing.u32("the job");
  const std::uint32_t backend = timing.u32("the backend");
  if (backend > std::uint32_t(BackendKind::cuda))
    throw std::runtime_error("job record: backend " + std::to_string(backend) + " is neither cpu (0) nor cuda (1)");
  r.backend = BackendKind(backend);
  r.device = timing.text("the device");
  r.frame_seconds = timing.list<double>(&Reader::f64, 8, "the frame times");
  timing.expect_end("run section");
  in.expect_end("run section");
  return r;
}

}  // namespace bleedsim
