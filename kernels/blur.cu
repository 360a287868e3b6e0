#include <cstddef>

#include "core/physics/blur.h"
#include "kernels/cuda_check.h"
#include "kernels/pixel_launch.h"

namespace bleedsim {
namespace {

__global__ void blur_kernel(BlurPhase phase, BlurArgs a) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  const int j = blockIdx.y * blockDim.y + threadIdx.y;
  if (phase == BlurPhase::upsample) {
    if (i < a.width && j < a.height) a.blurred[std::size_t(j) * a.width + i] = bilinear_up(a, i, j);
    return;
  }
  if (i >= a.low_width || j >= a.low_height) return;
  const std::size_t p = std::size_t(j) * a.low_width + i;
  if (phase == BlurPhase::downsample) a.low[p] = block_mean(a, i, j);
  else if (phase == BlurPhase::horizontal) a.across[p] = gaussian_tap_sum(a, a.low, i, j, true);
  else a.low[p] = gaussian_tap_sum(a, a.across, i, j, false);
}

}  // namespace

void cuda_twin(BlurPhase phase, const BlurArgs& a) {
  const bool full = phase == BlurPhase::upsample;
  const PixelLaunch launch = pixel_launch(full ? a.width : a.low_width, full ? a.height : a.low_height);
  blur_kernel<<<launch.blocks, launch.threads>>>(phase, a);
  check_launch("blur_kernel");
}

}  // namespace bleedsim
