// The CUDA twin of every per-particle functor in core/physics/particle_kernels.h: one kernel, a thread
// per live particle.
#include "core/physics/particle_kernels.h"
#include "kernels/cuda_check.h"

namespace bleedsim {
namespace {

constexpr int kThreads = 256;

template <class F>
__global__ void particle_kernel(F f) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < f.count()) f(t);
}

template <class F>
void launch_particles(const F& f, const char* name) {
  if (f.count() == 0) return;  // no grid of no blocks
  particle_kernel<<<(f.count() + kThreads - 1) / kThreads, kThreads>>>(f);
  check_launch(name);
}

}  // namespace

#define BLEEDSIM_CUDA_PARTICLE_TWIN(F) \
  void cuda_twin(const F& f) { launch_particles(f, #F); }
BLEEDSIM_PARTICLE_KERNELS(BLEEDSIM_CUDA_PARTICLE_TWIN)
#undef BLEEDSIM_CUDA_PARTICLE_TWIN

}  // namespace bleedsim
