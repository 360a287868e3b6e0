#include "core/physics/spread.h"

#include <cstddef>

#include "reference_cpu/parallel_rows.h"

namespace bleedsim {

void cpu_twin(const SpreadArgs& args, int threads) {
  const PixelGrid& grid = args.grid;
  parallel_rows(grid.height, threads, [&](int j) {
    float* row = args.stain + std::size_t(j) * grid.width;
    for (int i = 0; i < grid.width; ++i) row[i] = spread_stain(args.cuts, args.cut_count, grid, i, j);
  });
}

}  // namespace bleedsim
