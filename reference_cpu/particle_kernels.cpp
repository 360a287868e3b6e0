// The CPU twin of every per-particle functor in core/physics/particle_kernels.h: one loop, the live
// particles in bands over the threads (parallel_rows), each moved only by its own iteration, so any
// thread count gives the same bytes.
#include "core/physics/particle_kernels.h"

#include "reference_cpu/parallel_rows.h"

namespace bleedsim {

#define BLEEDSIM_CPU_PARTICLE_TWIN(F)                                                          \
  void cpu_twin(const F& f, int threads) {                                                     \
    parallel_rows(f.count(), threads_for_particles(f.count(), threads), [&](int t) { f(t); }); \
  }
BLEEDSIM_PARTICLE_KERNELS(BLEEDSIM_CPU_PARTICLE_TWIN)
#undef BLEEDSIM_CPU_PARTICLE_TWIN

}  // namespace bleedsim
