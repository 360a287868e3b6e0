// The CUDA twin of every per-pixel functor in core/physics/pixel_kernels.h: one kernel, a thread per
// pixel.
#include "core/physics/pixel_kernels.h"
#include "kernels/cuda_check.h"

namespace bleedsim {
namespace {

template <class F>
__global__ void pixel_kernel(F f) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  const int j = blockIdx.y * blockDim.y + threadIdx.y;
  if (i < f.width() && j < f.height()) f(i, j);
}

// 32 × 8 blocks: a warp spans 32 neighbouring pixels of a row, so loads and stores coalesce.
template <class F>
void launch_pixels(const F& f, const char* name) {
  const dim3 threads(32, 8);
  const dim3 blocks((f.width() + threads.x - 1) / threads.x, (f.height() + threads.y - 1) / threads.y);
  pixel_kernel<<<blocks, threads>>>(f);
  check_launch(name);
}

}  // namespace

#define BLEEDSIM_CUDA_PIXEL_TWIN(F) \
  void cuda_twin(const F& f) { launch_pixels(f, #F); }
BLEEDSIM_PIXEL_KERNELS(BLEEDSIM_CUDA_PIXEL_TWIN)
#undef BLEEDSIM_CUDA_PIXEL_TWIN

}  // namespace bleedsim
