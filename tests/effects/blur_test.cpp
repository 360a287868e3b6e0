// The blur's passes against what they must do: a flat film stays flat, a point spreads into the
// Gaussian's weights, a ramp survives the trip down and back up, and the edges clamp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <vector>

#include "core/effects/blur/blur_params.h"
#include "core/effects/blur/blur_stage.h"
#include "core/physics/pixel_kernels.h"

namespace bleedsim {
namespace {

struct Blurred {
  std::vector<float> film, weights, low, across, out;
  BlurArgs args{};

  Blurred(std::vector<float> input, int width, int height, int factor, int radius, double sigma)
      : film(std::move(input)), weights(gaussian_weights(radius, sigma)) {
    args.width = width;
    args.height = height;
    args.factor = factor;
    args.low_width = (width + factor - 1) / factor;
    args.low_height = (height + factor - 1) / factor;
    args.radius = radius;
    low.resize(std::size_t(args.low_width) * args.low_height);
    across.resize(low.size());
    out.resize(film.size());
    args.weights = weights.data();
    args.film = film.data();
    args.low = low.data();
    args.across = across.data();
    args.blurred = out.data();
    blur_passes(args).each([](const auto& pass) { cpu_twin(pass, 2); });
  }
};

TEST(Blur, TheWeightsAreTheNormalisedGaussian) {
  const std::vector<float> w = gaussian_weights(3, 1.5);
  ASSERT_EQ(w.size(), 7u);
  double sum = 0.0;
  for (float v : w) sum += v;
  EXPECT_NEAR(sum, 1.0, 1e-6);
  EXPECT_NEAR(w[3] / w[4], std::exp(0.5 / (1.5 * 1.5)), 1e-5);  // exp(−½(k/σ)²) ratios
  EXPECT_FLOAT_EQ(w[0], w[6]);
}

TEST(Blur, AFlatFilmStaysFlatEvenAtTheEdges) {
  const Blurred b(std::vector<float>(37 * 23, 0.25f), 37, 23, 4, 5, 2.0);  // sizes not multiples of 4
  for (float v : b.out) EXPECT_NEAR(v, 0.25f, 1e-6f);
}

TEST(Blur, APointSpreadsIntoTheWeights) {
  std::vector<float> film(21 * 21, 0.0f);
  film[10 * 21 + 10] = 1.0f;
  const Blurred b(film, 21, 21, 1, 3, 1.0);
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx)
      EXPECT_NEAR(b.out[(10 + dy) * 21 + 10 + dx], b.weights[dx + 3] * b.weights[dy + 3], 1e-7) << dx << "," << dy;
  EXPECT_NEAR(std::accumulate(b.out.begin(), b.out.end(), 0.0), 1.0, 1e-5);  // the blood is kept
}

TEST(Blur, ARampSurvivesDownAndUpsamplingInsideTheEdges) {
  const int w = 64, h = 8;
  std::vector<float> film(w * h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) film[j * w + i] = 0.01f * float(i);
  const Blurred b(film, w, h, 2, 0, 1.0);  // no blur taps: down and up only
  // Block means sit at the blocks' centres, and the bilinear upsample is exact on a line.
  for (int i = 2; i < w - 2; ++i) EXPECT_NEAR(b.out[3 * w + i], 0.01f * float(i), 1e-6f) << i;
  // At the edge it clamps: the first pixel takes the first block's mean.
  EXPECT_NEAR(b.out[3 * w], 0.005f, 1e-7f);
}

// The downsampling factors are one list, kBlurFactors: [blur].downsample allows exactly them, and
// each has an exact inverse, so a film of ones downsamples to exactly one (the block sums its
// factor² ones exactly, and scales by a power of two).
TEST(BlurFactors, TheTableAllowsExactlyTheListAndEachScalesExactly) {
  const Range& allowed = param_named(blur_table(), "downsample").range;
  EXPECT_EQ(allowed.only, std::vector<double>(std::begin(kBlurFactors), std::end(kBlurFactors)));
  for (int f = 0; f <= 8; ++f)
    EXPECT_EQ(allowed.contains(f), std::find(std::begin(kBlurFactors), std::end(kBlurFactors), f) !=
                                       std::end(kBlurFactors))
        << f;
  for (const int f : kBlurFactors) {
    EXPECT_EQ(inverse_factor(f) * float(f), 1.0f) << f;
    const Blurred b(std::vector<float>(16 * 8, 1.0f), 16, 8, f, 0, 1.0);
    for (const float v : b.low) EXPECT_EQ(v, 1.0f) << "factor " << f;
  }
}

}  // namespace
}  // namespace bleedsim