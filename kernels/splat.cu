#include <cstddef>

#include "core/physics/splat.h"
#include "kernels/cuda_check.h"
#include "kernels/pixel_launch.h"

namespace bleedsim {
namespace {

constexpr int kThreads = 256;

// Integer atomics: the sum of the deposits does not depend on their order.
__global__ void deposit_kernel(SplatArgs a) {
  const int slot = blockIdx.x * blockDim.x + threadIdx.x;
  if (slot >= a.capacity) return;
  auto* units = reinterpret_cast<unsigned long long*>(a.units);
  splat_particle(a, slot, [&](std::size_t pixel, std::uint64_t amount) {
    atomicAdd(units + pixel, static_cast<unsigned long long>(amount));
  });
}

__global__ void thickness_kernel(SplatArgs a) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  const int j = blockIdx.y * blockDim.y + threadIdx.y;
  if (i >= a.grid.width || j >= a.grid.height) return;
  const std::size_t p = std::size_t(j) * a.grid.width + i;
  a.thickness_mm[p] = thickness_from_units(a.units[p]);
}

}  // namespace

void cuda_twin(const SplatArgs& a) {
  const std::size_t pixels = std::size_t(a.grid.width) * std::size_t(a.grid.height);
  BLEEDSIM_CUDA_CHECK(cudaMemsetAsync(a.units, 0, pixels * sizeof(std::uint64_t)));
  deposit_kernel<<<(a.capacity + kThreads - 1) / kThreads, kThreads>>>(a);
  check_launch("deposit_kernel");
  const PixelLaunch launch = pixel_launch(a.grid.width, a.grid.height);
  thickness_kernel<<<launch.blocks, launch.threads>>>(a);
  check_launch("thickness_kernel");
}

}  // namespace bleedsim
