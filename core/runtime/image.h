#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

namespace bleedsim {

// An 8-bit RGBA image in host memory, row-major, top row first.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width × height × 4
};

// An 8-bit code value as a fraction of full scale, and back with round-half-up (clamped first: a
// value off [0, 1], or not a number, becomes the nearest end). No gamma: the code values themselves.
inline float unit_from_byte(std::uint8_t v) { return static_cast<float>(v) / 255.0f; }
inline std::uint8_t byte_from_unit(float v) {
  const float clamped = std::fmin(std::fmax(v, 0.0f), 1.0f);  // fmax of NaN and 0 is 0
  return static_cast<std::uint8_t>(clamped * 255.0f + 0.5f);
}

}  // namespace bleedsim
