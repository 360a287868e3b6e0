#pragma once
// The per-particle work of the hooks in the particle step, as functors: F{...}(t) acts on the t-th
// live particle, of F::count(), and on no other, so the particles can run in any order. One loop
// (reference_cpu/particle_kernels.cpp) and one kernel (kernels/particle_kernels.cu) run them all: a
// hook's per-particle work needs only its functor, in its physics header, and a line here.
#include "core/physics/instrument.h"

#define BLEEDSIM_PARTICLE_KERNELS(X) X(KeepOutOfTip)

namespace bleedsim {

// The twins of each: over host memory on `threads` threads, and over device memory.
#define BLEEDSIM_DECLARE_PARTICLE_TWINS(F) \
  void cpu_twin(const F& f, int threads);  \
  void cuda_twin(const F& f);
BLEEDSIM_PARTICLE_KERNELS(BLEEDSIM_DECLARE_PARTICLE_TWINS)
#undef BLEEDSIM_DECLARE_PARTICLE_TWINS

}  // namespace bleedsim
