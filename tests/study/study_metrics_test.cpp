// The accuracy study's metrics (core/study/study_metrics.cpp) on fields whose values are known by
// hand: area resampling, the pile's height, the blood front, a frame's measures and one run's
// distance from another.
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

TEST(FrameMeasuresTest, VolumeAreaFrontAndPileOfAKnownFilm) {
  // 8 pixels of 4 mm², 0.04 mm deep: 1.28 mm³ over 32 mm², all of it covered, so the front is the
  // lowest cell's centre (y = 3 mm on a 2-row grid of 2 mm cells) and the pile fills every column.
  const FrameFields f = frame(0.04f, 100);
  const std::vector<float> grid = film_on_grid(f, 4, 2);
  const FrameMeasures m = measure_frame(f, grid, 4, 2, 0.0, 1000.0);
  EXPECT_NEAR(m.volume_mm3, 8 * 4.0 * 0.04, 1e-6);
  EXPECT_NEAR(m.covered_area_mm2, 32.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.front_mm, 3.0);
  EXPECT_DOUBLE_EQ(m.pile_height_mm, 4.0);
  FrameFields none = frame(0.0f, 100);
  none.film_mm.clear();
  EXPECT_TRUE(std::isnan(measure_frame(none, {}, 4, 2, 0.0, 1000.0).volume_mm3));
}

TEST(BloodFront, IsTheFarthestCoveredCellAlongGravity) {
  // 4 × 4 cells of 1 mm; one covered cell at column 2, row 1 (centre (2.5, 1.5) mm).
  std::vector<float> film(16, 0.0f);
  EXPECT_EQ(blood_front_mm(film, 4, 4, 4, 4, 0, 1000), 0.0);  // nothing covered
  film[1 * 4 + 2] = 0.05f;
  EXPECT_DOUBLE_EQ(blood_front_mm(film, 4, 4, 4, 4, 0, 1000), 1.5);    // down: its y
  EXPECT_DOUBLE_EQ(blood_front_mm(film, 4, 4, 4, 4, -1000, 0), 1.5);   // to the left: from the right edge, 4 − 2.5
  // Down and to the right at 45°: (2.5 + 1.5)/√2 from the top-left corner.
  EXPECT_NEAR(blood_front_mm(film, 4, 4, 4, 4, 1000, 1000), 4.0 / std::sqrt(2.0), 1e-12);
  film[3 * 4 + 0] = 0.011f;  // just covered, lower down
  EXPECT_DOUBLE_EQ(blood_front_mm(film, 4, 4, 4, 4, 0, 1000), 3.5);
}

TEST(RestTime, TheFastestIsOfTheLiveParticlesOnly) {
  // Three slots: one live at (3, 4) mm/s (speed 5), one past its lifetime of 10 steps moving at
  // 100, one live at rest.
  const std::vector<float> velocity{3, 4, 100, 0, 0, 0};
  const ParticleLifetime ten{10, 0};
  EXPECT_DOUBLE_EQ(fastest_speed_mm_s(velocity, {2, 10, 9}, ten), 5.0);
  EXPECT_DOUBLE_EQ(fastest_speed_mm_s(velocity, {10, 11, 9}, ten), 0.0);  // the live one at rest
  EXPECT_DOUBLE_EQ(fastest_speed_mm_s({}, {}, ten), 0.0);                  // none
}

TEST(RestTime, IsTheEndOfTheLastFrameFasterThanTheRestSpeed) {
  // Frames of 0.1 s: moving in frames 0–2 and 4 (frame 3 a pause), then at the rest speed exactly
  // (not faster) and still: the blood rests from the end of frame 4, 0.5 s.
  EXPECT_DOUBLE_EQ(rest_time_s({50, 2, 0.2, 0, 0.11, kRestSpeedMmS, 0}, 0.1), 0.5);
  EXPECT_DOUBLE_EQ(rest_time_s({0, 0, 0}, 0.1), 0.0);      // never moved faster
  EXPECT_DOUBLE_EQ(rest_time_s({0, 0, 1.0}, 0.1), 0.3);    // still moving at the end: the run's end
}

TEST(RunDistanceTest, KnownDifferencesGiveKnownDistances) {
  const GridFrame reference = on_grid(frame(0.04f, 100), 2, 1);
  const GridFrame run = on_grid(frame(0.05f, 106), 2, 1);  // compared on a coarser grid
  const RunDistance d = run_distance(run, reference);
  EXPECT_NEAR(d.film_l1_mm, 0.01, 1e-7);
  EXPECT_NEAR(d.film_l2_mm, 0.01, 1e-7);
  EXPECT_NEAR(d.frame_mse, 36.0 / 3.0, 1e-9);  // green off by 6 in one channel of three
  EXPECT_NEAR(psnr_db(d.frame_mse), 10 * std::log10(255.0 * 255.0 / 12.0), 1e-9);
  EXPECT_EQ(d.stain_l1, 0.0);
  EXPECT_TRUE(std::isinf(psnr_db(0.0)));
}

TEST(RunDistanceTest, ASceneWithoutAFieldHasNoDistanceForIt) {
  FrameFields a = frame(0.0f, 100), b = frame(0.0f, 100);
  a.film_mm.clear();
  b.film_mm.clear();
  a.stain.clear();
  b.stain.clear();
  const RunDistance d = run_distance(on_grid(a, 4, 2), on_grid(b, 4, 2));
  EXPECT_TRUE(std::isnan(d.film_l1_mm));
  EXPECT_TRUE(std::isnan(d.stain_l1));
  EXPECT_EQ(d.frame_mse, 0.0);
}

TEST(CommonGrid, NoFinerThanItsLimitAndTheAspectKept) {
  int w = 640, h = 480;
  common_grid(w, h);
  EXPECT_EQ(w, kMaxGridWidth);
  EXPECT_EQ(h, 120);
  int small_w = 120, small_h = 90;
  common_grid(small_w, small_h);
  EXPECT_EQ(small_w, 120);
  EXPECT_EQ(small_h, 90);
}

}  // namespace
}  // namespace bleedsim
