// The CUDA twin of the splat: a thread per slot deposits with integer atomics, then the per-pixel
// conversion.
#include <cstddef>

#include "core/physics/pixel_kernels.h"
#include "core/physics/splat.h"
#include "kernels/cuda_check.h"

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

}  // namespace

void cuda_twin(const SplatArgs& a) {
  const std::size_t pixels = std::size_t(a.grid.width) * std::size_t(a.grid.height);
  BLEEDSIM_CUDA_CHECK(cudaMemsetAsync(a.units, 0, pixels * sizeof(std::uint64_t)));
  deposit_kernel<<<(a.capacity + kThreads - 1) / kThreads, kThreads>>>(a);
  check_launch("deposit_kernel");
  cuda_twin(splat_thickness(a));
}

}  // namespace bleedsim
