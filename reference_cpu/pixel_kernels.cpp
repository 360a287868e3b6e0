// The CPU twin of every per-pixel functor in core/physics/pixel_kernels.h: one loop, rows in bands
// over the threads (parallel_rows), each pixel written by exactly one of them.
#include "core/physics/pixel_kernels.h"

#include "reference_cpu/parallel_rows.h"

namespace bleedsim {
namespace {

template <class F>
void for_each_pixel(const F& f, int threads) {
  const int width = f.width();
  parallel_rows(f.height(), threads, [&](int j) {
    for (int i = 0; i < width; ++i) f(i, j);
  });
}

}  // namespace

#define BLEEDSIM_CPU_PIXEL_TWIN(F) \
  void cpu_twin(const F& f, int threads) { for_each_pixel(f, threads); }
BLEEDSIM_PIXEL_KERNELS(BLEEDSIM_CPU_PIXEL_TWIN)
#undef BLEEDSIM_CPU_PIXEL_TWIN

}  // namespace bleedsim
