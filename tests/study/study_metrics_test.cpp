// The accuracy study's metrics (core/study/study_metrics.cpp) on fields whose errors are known by hand:
// area resampling, the pile's height, and each error against a reference.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/study/study_metrics.h"

namespace bleedsim {
namespace {

TEST(AreaResample, BlockMeansWhenTheRatioIsWhole) {
  // 4 × 2 → 2 × 1: each output cell is the mean of a 2 × 2 block.
  const std::vector<double> in = {1, 2, 3, 4,
                                  5, 6, 7, 8};
  EXPECT_EQ(area_resample(in, 4, 2, 2, 1), (std::vector<double>{3.5, 5.5}));
}

TEST(AreaResample, SplitsStraddlingPixelsByArea) {
  // 3 → 2 across: cell 0 covers pixels [0, 1.5), cell 1 [1.5, 3): (1 + ½·2) / 1.5 and (½·2 + 3) / 1.5.
  const std::vector<double> out = area_resample({1, 2, 3}, 3, 1, 2, 1);
  EXPECT_NEAR(out[0], 2.0 / 1.5, 1e-15);
  EXPECT_NEAR(out[1], 4.0 / 1.5, 1e-15);
  // Upsampling repeats: 1 → 3 cells of the same value; a constant field stays constant either way.
  for (const double v : area_resample({7}, 1, 1, 3, 1)) EXPECT_NEAR(v, 7.0, 1e-14);
  for (const double v : area_resample(std::vector<double>(35, 0.25), 7, 5, 3, 2)) EXPECT_NEAR(v, 0.25, 1e-15);
}

TEST(AreaResample, KeepsChannelsApart) {
  // Two pixels of RGB, one cell: each channel's own mean.
  EXPECT_EQ(area_resample({10, 20, 30, 30, 40, 50}, 2, 1, 1, 1, 3), (std::vector<double>{20, 30, 40}));
  EXPECT_THROW(area_resample({1, 2, 3}, 2, 1, 1, 1), std::invalid_argument);
}

TEST(PileHeight, CountsCoveredCellsFromTheBottomUntilTheFirstGap) {
  // 3 columns × 4 rows, 0.5 mm cells. Column 0: covered from the bottom up 2 cells, then a gap, then
  // blood again (not the pile). Column 1: nothing at the bottom. Column 2: all 4.
  const float c = 0.05f, o = 0.0f;
  const std::vector<float> film = {c, o, c,
                                   o, o, c,
                                   c, o, c,
                                   c, c - c, c};
  EXPECT_EQ(pile_heights_mm(film, 3, 4, 0.5), (std::vector<double>{1.0, 0.0, 2.0}));
}

// A 4 × 2 px frame over an 8 × 4 mm panel (2 mm pixels, 4 mm² each).
FrameFields frame(float film, std::uint8_t green) {
  FrameFields f;
  f.width = 4;
  f.height = 2;
  f.width_mm = 8;
  f.height_mm = 4;
  f.film_mm.assign(8, film);
  f.stain.assign(8, 0.5f);
  for (int p = 0; p < 8; ++p) f.rgba.insert(f.rgba.end(), {200, green, 100, 255});
  return f;
}

TEST(FrameErrorsTest, KnownDifferencesGiveKnownErrors) {
  const GridFrame reference = on_grid(frame(0.04f, 100), 4, 2);
  EXPECT_NEAR(reference.volume_mm3, 8 * 4.0 * 0.04, 1e-6);  // 8 pixels of 4 mm², 0.04 mm deep
  EXPECT_NEAR(reference.covered_area_mm2, 32.0, 1e-12);
  const GridFrame run = on_grid(frame(0.05f, 106), 2, 1);  // compared on a coarser grid
  const FrameErrors e = compare(run, on_grid(frame(0.04f, 100), 2, 1));
  EXPECT_NEAR(e.film_l1_mm, 0.01, 1e-7);
  EXPECT_NEAR(e.film_l2_mm, 0.01, 1e-7);
  EXPECT_NEAR(e.frame_mse, 36.0 / 3.0, 1e-9);  // green off by 6 in one channel of three
  EXPECT_NEAR(psnr_db(e.frame_mse), 10 * std::log10(255.0 * 255.0 / 12.0), 1e-9);
  EXPECT_NEAR(e.volume_rel_error, 0.25, 1e-6);  // 0.05 against 0.04
  EXPECT_EQ(e.covered_area_rel_error, 0.0);     // both fully covered
  EXPECT_EQ(e.stain_l1, 0.0);
  EXPECT_EQ(e.pile_height_error_mm, 0.0);       // both piles reach the top
  EXPECT_TRUE(std::isinf(psnr_db(0.0)));
}

TEST(FrameErrorsTest, ASceneWithoutAFieldHasNoErrorForIt) {
  FrameFields a = frame(0.0f, 100), b = frame(0.0f, 100);
  a.film_mm.clear();
  b.film_mm.clear();
  a.stain.clear();
  b.stain.clear();
  const FrameErrors e = compare(on_grid(a, 4, 2), on_grid(b, 4, 2));
  EXPECT_TRUE(std::isnan(e.film_l1_mm));
  EXPECT_TRUE(std::isnan(e.stain_l1));
  EXPECT_TRUE(std::isnan(e.volume_rel_error));
  EXPECT_EQ(e.frame_mse, 0.0);
}

TEST(CommonGrid, NoFinerThanItsLimitAndTheAspectKept) {
  int w = 640, h = 480;
  common_grid(w, h);
  EXPECT_EQ(w, kMaxGridWidth);
  EXPECT_EQ(h, 240);
  int small_w = 160, small_h = 120;
  common_grid(small_w, small_h);
  EXPECT_EQ(small_w, 160);
  EXPECT_EQ(small_h, 120);
}

}  // namespace
}  // namespace bleedsim
