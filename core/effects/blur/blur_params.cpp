#include "core/effects/blur/blur_params.h"

#include <algorithm>
#include <iterator>
#include <vector>

#include "core/physics/blur.h"

namespace bleedsim {
namespace {

// A file that gives no sigma gets half the radius (at least half a pixel): the taps then reach
// two sigmas, where the Gaussian is down to 14 %.
ParamProblem sigma_from_radius(BlurParams& b, const Written& written, const Scene&) {
  if (!written.has("sigma_px")) b.sigma_px = std::max(0.5, b.radius_px / 2.0);
  return {};
}

}  // namespace

const ParamTable<BlurParams>& blur_table() {
  using P = BlurParams;
  const Range factors(kBlurFactors[0], *std::rbegin(kBlurFactors), false,
                      std::vector<double>(std::begin(kBlurFactors), std::end(kBlurFactors)));
  static const ParamTable<P> table{
      "blur",
      "declares the blur of the particles' film of blood (needs [particles])",
      {{"downsample", ParamType::integer, BLEEDSIM_MEMBER(P, downsample), "", factors,
        "the film is blurred at 1/downsample of the panel's resolution"},
       {"radius_px", ParamType::integer, BLEEDSIM_MEMBER(P, radius_px), "downsampled px", {0, 64},
        "Gaussian taps either side, in downsampled pixels"},
       {"sigma_px", ParamType::number, BLEEDSIM_MEMBER(P, sigma_px), "downsampled px", {0, 64, true},
        "the Gaussian's width, in downsampled pixels", "max(0.5, radius_px / 2)"}},
      {},
      sigma_from_radius};
  return table;
}

}  // namespace bleedsim
