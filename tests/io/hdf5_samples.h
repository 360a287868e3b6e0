#pragma once
// The frames the HDF5 writer's tests write: a 7 × 5 image field and a stain per frame, and
// per-element arrays (positions, counts, ids) beside them, each frame's values its own.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/io/hdf5_writer.h"
#include "tests/io/hdf5_read_back.h"

namespace bleedsim::test {

// ---- What the tests write ------------------------------------------------------------------------

constexpr int kWidth = 7;
constexpr int kHeight = 5;
constexpr int kFrames = 3;
constexpr int kPixels = kWidth * kHeight;

using Attributes = std::vector<std::pair<std::string, std::string>>;

inline const Attributes kAttributes = {{"bleedsim_version", "0.1.0"},
                                       {"scenario_text", "[spread]\nradius_mm = 4.0  # Ø 8 mm wound\n"}};

inline std::vector<FieldLayout> sample_fields() {
  return {{"frame", ElementType::u8, 4, kWidth, kHeight, "", "composited frame, RGBA8"},
          {"spread/stain", ElementType::f32, 1, kWidth, kHeight, "1", "stain coverage"}};
}

// Every byte differs from its neighbours and from the same byte of the other frames.
inline std::vector<std::uint8_t> frame_pattern(int frame) {
  std::vector<std::uint8_t> rgba(std::size_t(kPixels) * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i)
    rgba[i] = std::uint8_t(i * 7 + 31 * std::size_t(frame));
  return rgba;
}

inline std::vector<float> stain_values(int frame) {
  std::vector<float> stain(kPixels);
  for (int i = 0; i < kPixels; ++i) stain[std::size_t(i)] = 0.1f * float(i) - 1.5f + float(frame);
  return stain;
}

inline double frame_time(int frame) { return (frame + 1) / 30.0; }

inline void append_sample_frame(Hdf5FrameWriter& writer, int frame) {
  const std::vector<std::uint8_t> rgba = frame_pattern(frame);
  const std::vector<float> stain = stain_values(frame);
  writer.append(frame_time(frame), {rgba.data(), stain.data()});
}

inline void write_sample(const std::filesystem::path& path, int deflate_level,
                  const Attributes& attributes = kAttributes) {
  Hdf5FrameWriter writer(path.string(), sample_fields(), attributes, deflate_level);
  for (int frame = 0; frame < kFrames; ++frame) append_sample_frame(writer, frame);
  writer.finish(true);
}

// --- Per-element arrays (image == false): particles and counters ---------------------------------

constexpr int kSlots = 5;     // particle ring-buffer capacity
constexpr int kCounters = 4;  // accounting counters

inline std::vector<FieldLayout> array_fields() {
  std::vector<FieldLayout> fields = sample_fields();
  fields.push_back({"particles/position", ElementType::f32, 2, kSlots, 1, "m",
                    "particle position (x, y), one per ring-buffer slot", false});
  fields.push_back({"particles/accounting", ElementType::u64, 1, kCounters, 1, "1",
                    "particle counters", false});
  fields.push_back({"particles/id", ElementType::u32, 1, kSlots, 1, "", "particle id per slot",
                    false});
  return fields;
}

// (x, y) per slot, x and y interleaved as in memory ([slot][component]), different in every slot,
// component and frame.
inline std::vector<float> position_values(int frame) {
  std::vector<float> xy(std::size_t(kSlots) * 2);
  for (std::size_t i = 0; i < xy.size(); ++i)
    xy[i] = 0.375f * float(i) - 1.25f + 10.0f * float(frame) + (i % 2 ? 0.001f : 0.0f);
  return xy;
}

// Beyond 2^53 and 2^63, so a detour through double or a signed type would show.
inline std::vector<std::uint64_t> accounting_values(int frame) {
  const std::uint64_t f = std::uint64_t(frame);
  return {f + 1, (std::uint64_t(1) << 40) + 3 * f, 0xFFFFFFFFFFFFFFF0ull + f,
          0x0123456789ABCDEFull * (f + 1)};
}

// Beyond 2^31, so a signed 32-bit detour would show.
inline std::vector<std::uint32_t> id_values(int frame) {
  std::vector<std::uint32_t> ids(kSlots);
  for (int i = 0; i < kSlots; ++i)
    ids[std::size_t(i)] = 0xF0000000u + std::uint32_t(i) * 7u + std::uint32_t(frame) * 100u;
  return ids;
}

inline void write_array_sample(const std::filesystem::path& path, int deflate_level,
                        const Attributes& attributes = kAttributes) {
  Hdf5FrameWriter writer(path.string(), array_fields(), attributes, deflate_level);
  for (int frame = 0; frame < kFrames; ++frame) {
    const std::vector<std::uint8_t> rgba = frame_pattern(frame);
    const std::vector<float> stain = stain_values(frame);
    const std::vector<float> position = position_values(frame);
    const std::vector<std::uint64_t> accounting = accounting_values(frame);
    const std::vector<std::uint32_t> ids = id_values(frame);
    writer.append(frame_time(frame),
                  {rgba.data(), stain.data(), position.data(), accounting.data(), ids.data()});
  }
  writer.finish(true);
}

inline std::filesystem::path test_folder() { return test_output_folder("hdf5_writer"); }

}  // namespace bleedsim::test
