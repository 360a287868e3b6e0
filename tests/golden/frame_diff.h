#pragma once
// What differs between an expected and an actual field, for a golden test's failure message.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/state.h"

namespace bleedsim::golden {

struct DiffStats {
  std::size_t values = 0;     // elements compared (pixels × channels)
  std::size_t differing = 0;
  double max_abs_error = 0.0;
  double psnr_db = 0.0;       // infinite when equal; peak 255 for bytes, 1 for float fields,
                              // the largest value in either for u32/u64 fields
  std::size_t first = 0;      // index of the first differing element
  double expected = 0.0, actual = 0.0;
  std::uint64_t expected_integer = 0, actual_integer = 0;  // integer fields: the same, exactly
  std::int64_t ulps = 0;      // float fields: ulp distance at the first difference; 0 otherwise
};

// Distance in units in the last place: how many floats lie between a and b.
std::int64_t ulp_distance(float a, float b);

DiffStats diff_field(const FieldLayout& layout, const std::vector<std::uint8_t>& expected,
                     const std::vector<std::uint8_t>& actual);

// "312 of 19200 values differ, max abs error 1.2e-07, PSNR 139.2 dB; first at (x 40, y 33,
//  channel 0): got 0.5123 expected 0.5122 (2 ulp)"; a field that is not an image names
//  "(element 17, component 1)" instead. u32/u64 fields compare as integers.
std::string describe(const FieldLayout& layout, const DiffStats& stats);

// Writes <prefix>expected.png, <prefix>actual.png and <prefix>diff.png (differences amplified);
// nothing for a field that is not an image.
void write_diff_images(const std::string& prefix, const FieldLayout& layout,
                       const std::vector<std::uint8_t>& expected, const std::vector<std::uint8_t>& actual);

}  // namespace bleedsim::golden
