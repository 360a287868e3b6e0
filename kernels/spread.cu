#include <cstddef>

#include "core/physics/spread.h"
#include "kernels/cuda_check.h"
#include "kernels/pixel_launch.h"

namespace bleedsim {
namespace {

__global__ void spread_kernel(SpreadArgs args) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  const int j = blockIdx.y * blockDim.y + threadIdx.y;
  if (i >= args.grid.width || j >= args.grid.height) return;
  args.stain[std::size_t(j) * args.grid.width + i] =
      spread_stain(args.cuts, args.cut_count, args.grid, i, j);
}

}  // namespace

void cuda_twin(const SpreadArgs& args) {
  const PixelLaunch launch = pixel_launch(args.grid.width, args.grid.height);
  spread_kernel<<<launch.blocks, launch.threads>>>(args);
  check_launch("spread_kernel");
}

}  // namespace bleedsim
