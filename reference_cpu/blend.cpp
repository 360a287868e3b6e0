#include "core/physics/blend.h"

#include <cstddef>

#include "reference_cpu/parallel_rows.h"

namespace bleedsim {

void cpu_twin(const BlendArgs& args, int threads) {
  parallel_rows(args.height, threads, [&](int j) {
    for (int i = 0; i < args.width; ++i) {
      const std::size_t p = std::size_t(j) * args.width + i;
      blend_pixel(args.tissue_rgba + 4 * p, args.stain ? args.stain[p] : 0.0f,
                  args.thickness_mm ? args.thickness_mm[p] : 0.0f, args.transmission, args.frame_rgba + 4 * p);
    }
  });
}

}  // namespace bleedsim
