#include "core/physics/blur.h"
#include "reference_cpu/parallel_rows.h"

namespace bleedsim {

void cpu_twin(BlurPhase phase, const BlurArgs& a, int threads) {
  const auto low_rows = [&](auto value_at, float* out) {
    parallel_rows(a.low_height, threads, [&](int j) {
      for (int i = 0; i < a.low_width; ++i) out[std::size_t(j) * a.low_width + i] = value_at(i, j);
    });
  };
  switch (phase) {
    case BlurPhase::downsample:
      low_rows([&](int i, int j) { return block_mean(a, i, j); }, a.low);
      break;
    case BlurPhase::horizontal:
      low_rows([&](int i, int j) { return gaussian_tap_sum(a, a.low, i, j, true); }, a.across);
      break;
    case BlurPhase::vertical:
      low_rows([&](int i, int j) { return gaussian_tap_sum(a, a.across, i, j, false); }, a.low);
      break;
    case BlurPhase::upsample:
      parallel_rows(a.height, threads, [&](int j) {
        for (int i = 0; i < a.width; ++i) a.blurred[std::size_t(j) * a.width + i] = bilinear_up(a, i, j);
      });
      break;
  }
}

}  // namespace bleedsim
