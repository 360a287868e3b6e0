#include <cstddef>
#include <cstdint>

#include "core/physics/blend.h"
#include "kernels/cuda_check.h"
#include "kernels/pixel_launch.h"

namespace bleedsim {
namespace {

__global__ void blend_kernel(BlendArgs args) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  const int j = blockIdx.y * blockDim.y + threadIdx.y;
  if (i >= args.width || j >= args.height) return;
  const std::size_t p = std::size_t(j) * args.width + i;
  // One 4-byte load and store per pixel instead of four single bytes.
  const uchar4 tissue = reinterpret_cast<const uchar4*>(args.tissue_rgba)[p];
  const std::uint8_t in[4] = {tissue.x, tissue.y, tissue.z, tissue.w};
  std::uint8_t out[4];
  blend_pixel(in, args.stain ? args.stain[p] : 0.0f, args.thickness_mm ? args.thickness_mm[p] : 0.0f,
              args.transmission, out);
  reinterpret_cast<uchar4*>(args.frame_rgba)[p] = make_uchar4(out[0], out[1], out[2], out[3]);
}

}  // namespace

void cuda_twin(const BlendArgs& args) {
  const PixelLaunch launch = pixel_launch(args.width, args.height);
  blend_kernel<<<launch.blocks, launch.threads>>>(args);
  check_launch("blend_kernel");
}

}  // namespace bleedsim
