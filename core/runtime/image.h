#pragma once
#include <cstdint>
#include <vector>

namespace bleedsim {

// An 8-bit RGBA image in host memory, row-major, top row first.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width × height × 4
};

}  // namespace bleedsim
