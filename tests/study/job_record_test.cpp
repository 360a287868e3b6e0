// A study job's record (core/study/job_record.cpp): its bytes round-trip to the bit (NaN and
// infinities included), its data bytes leave the timing out, and bytes that are not a record of
// this version are refused with a message saying what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/study/job_record.h"

namespace bleedsim {
namespace {

JobRecord sample() {
  JobRecord r;
  r.study_key = 0x0123456789abcdefULL;
  r.job = 7;
  r.setting = 3;
  r.seed_index = 1;
  r.seed = (1ULL << 62) + 5;
  r.status = "ok, with a comma and ü";
  r.front_mm = {0.0, 1.5, std::numeric_limits<double>::quiet_NaN()};
  r.covered_area_mm2 = {2.0, -0.0, std::numeric_limits<double>::infinity()};
  r.volume_mm3 = {1e-300, 4.9e-324};  // the smallest normal's neighbourhood and a subnormal
  r.pile_height_mm = {};
  r.fastest_mm_s = {0.0, 0.1, 99.5};
  r.grid_width = 2;
  r.grid_height = 1;
  r.snapshot_frames = {0, -1, 2147483647};
  r.film_mm = {0.25f, 1e-40f};
  r.rgb = {255.0f, 0.5f, 3.0f, 4.0f, 5.0f, 6.0f};
  r.backend = BackendKind::cuda;
  r.device = "NVIDIA H200 (sm_90, 140 GiB)";
  r.frame_seconds = {0.001, 0.002};
  return r;
}

// Bitwise: NaN == NaN and −0 ≠ +0, as the bytes see them.
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

TEST(JobRecord, RoundTripsToTheBit) {
  const JobRecord r = sample();
  const std::vector<std::uint8_t> bytes = serialize(r);
  const JobRecord back = deserialize(bytes);
  EXPECT_EQ(back.study_key, r.study_key);
  EXPECT_EQ(back.job, r.job);
  EXPECT_EQ(back.setting, r.setting);
  EXPECT_EQ(back.seed_index, r.seed_index);
  EXPECT_EQ(back.seed, r.seed);
  EXPECT_EQ(back.status, r.status);
  EXPECT_TRUE(same_bits(back.front_mm, r.front_mm));
  EXPECT_TRUE(same_bits(back.covered_area_mm2, r.covered_area_mm2));
  EXPECT_TRUE(same_bits(back.volume_mm3, r.volume_mm3));
  EXPECT_TRUE(back.pile_height_mm.empty());
  EXPECT_TRUE(same_bits(back.fastest_mm_s, r.fastest_mm_s));
  EXPECT_EQ(back.grid_width, 2);
  EXPECT_EQ(back.grid_height, 1);
  EXPECT_EQ(back.snapshot_frames, r.snapshot_frames);
  EXPECT_TRUE(same_bits(back.film_mm, r.film_mm));
  EXPECT_TRUE(back.stain.empty());
  EXPECT_TRUE(same_bits(back.rgb, r.rgb));
  EXPECT_EQ(back.backend, BackendKind::cuda);
  EXPECT_EQ(back.device, r.device);
  EXPECT_TRUE(same_bits(back.frame_seconds, r.frame_seconds));
  EXPECT_EQ(serialize(back), bytes);
}

TEST(JobRecord, IsLittleEndianWhateverTheHost) {
  // The magic, then the version 2 as four little-endian bytes, then the data section's length.
  const std::vector<std::uint8_t> bytes = serialize(sample());
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 8), "BSJOBREC");
  EXPECT_EQ((std::vector<std::uint8_t>(bytes.begin() + 8, bytes.begin() + 12)), (std::vector<std::uint8_t>{2, 0, 0, 0}));
  // The study key is the data section's first field: 0x0123456789abcdef, lowest byte first.
  EXPECT_EQ(bytes[20], 0xef);
  EXPECT_EQ(bytes[27], 0x01);
}

TEST(JobRecord, DataBytesLeaveTheTimingOut) {
  JobRecord a = sample(), b = sample();
  b.backend = BackendKind::cpu;
  b.device = "cpu (2 threads)";
  b.frame_seconds = {0.5};
  EXPECT_EQ(data_bytes(a), data_bytes(b));
  EXPECT_NE(serialize(a), serialize(b));
  b.film_mm[0] = std::nextafter(b.film_mm[0], 1.0f);  // one ulp of one cell
  EXPECT_NE(data_bytes(a), data_bytes(b));
}

std::string refusal(const std::vector<std::uint8_t>& bytes) {
  try {
    deserialize(bytes);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(JobRecord, RefusesWhatIsNotARecordOfThisVersion) {
  const std::vector<std::uint8_t> bytes = serialize(sample());
  EXPECT_NE(refusal({'h', 'e', 'l', 'l', 'o'}).find("not a bleedsim study job record"), std::string::npos);
  std::vector<std::uint8_t> version = bytes;
  version[8] = 1;  // the records before the fastest particle was kept
  EXPECT_NE(refusal(version).find("version 1; this bleedsim reads version 2"), std::string::npos);
  // Cut anywhere, it is refused (never read past its end), saying it is truncated.
  for (std::size_t cut = 8; cut < bytes.size(); cut += 7) {
    const std::string why = refusal(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + long(cut)));
    EXPECT_NE(why.find("truncated"), std::string::npos) << cut << ": " << why;
  }
  std::vector<std::uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_NE(refusal(longer).find("1 bytes left over"), std::string::npos) << refusal(longer);
  // A count that the bytes left cannot hold (a garbled length) is refused before anything is allocated.
  std::vector<std::uint8_t> garbled = bytes;
  for (int i = 0; i < 8; ++i) garbled[12 + std::size_t(i)] = 0xff;
  EXPECT_NE(refusal(garbled).find("truncated"), std::string::npos) << refusal(garbled);
}

}  // namespace
}  // namespace bleedsim
