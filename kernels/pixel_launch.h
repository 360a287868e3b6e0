#pragma once
#include <cuda_runtime.h>

namespace bleedsim {

// One thread per pixel in 32 × 8 blocks: a warp spans 32 neighbouring pixels of a row, so loads
// and stores coalesce.
struct PixelLaunch {
  dim3 blocks;
  dim3 threads;
};

inline PixelLaunch pixel_launch(int width, int height) {
  const dim3 threads(32, 8);
  return {dim3((width + threads.x - 1) / threads.x, (height + threads.y - 1) / threads.y), threads};
}

}  // namespace bleedsim
