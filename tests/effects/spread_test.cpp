// The radial spread's physics (core/physics/spread.h), checked against values worked out by hand.
#include <gtest/gtest.h>

#include "core/physics/spread.h"

namespace bleedsim {
namespace {

TEST(StainProfile, IsOneAtTheCentreAndZeroFromTheRadiusOut) {
  EXPECT_EQ(stain_profile(0.0f, 3.0f), 1.0f);
  EXPECT_EQ(stain_profile(3.0f, 3.0f), 0.0f);
  EXPECT_EQ(stain_profile(7.5f, 3.0f), 0.0f);
}

TEST(StainProfile, IsTheSixthPowerOfTheRemainingFraction) {
  // (r − d)/r = ½ → 1/64, and ¼ → 1/4096: powers of two, exact in float.
  EXPECT_EQ(stain_profile(2.0f, 4.0f), 1.0f / 64.0f);
  EXPECT_EQ(stain_profile(3.0f, 4.0f), 1.0f / 4096.0f);
  // 0.9^6 = 0.531441.
  EXPECT_NEAR(stain_profile(0.5f, 5.0f), 0.531441f, 1e-6f);
}

TEST(StainProfile, FallsMonotonicallyWithDistance) {
  float previous = 2.0f;
  for (int i = 0; i <= 100; ++i) {
    const float value = stain_profile(0.05f * float(i), 5.0f);
    EXPECT_LE(value, previous) << "at d = " << 0.05f * float(i);
    previous = value;
  }
}

TEST(CutStain, ScalesTheProfileByTheAmplitudeAndIsRadial) {
  const SpreadCut cut{10.0f, 10.0f, 4.0f, 0.5f};
  EXPECT_EQ(cut_stain(cut, 10.0f, 10.0f), 0.5f);
  EXPECT_EQ(cut_stain(cut, 12.0f, 10.0f), 0.5f / 64.0f);
  // The same distance in each direction gives the same stain.
  EXPECT_EQ(cut_stain(cut, 8.0f, 10.0f), cut_stain(cut, 10.0f, 12.0f));
  EXPECT_EQ(cut_stain(cut, 10.0f, 8.0f), cut_stain(cut, 12.0f, 10.0f));
  EXPECT_EQ(cut_stain(cut, 14.0f, 10.0f), 0.0f);
  EXPECT_EQ(cut_stain(cut, 13.0f, 13.0f), 0.0f);  // inside the bounding square, outside the circle
}

TEST(SpreadStain, CombinesOverlappingCutsAsIndependentAbsorbers) {
  // Two half-strength stains on one pixel: half the light passes each, a quarter passes both.
  const PixelGrid grid{4, 4, 1.0f, 1.0f};
  const SpreadCut cuts[] = {{1.5f, 1.5f, 2.0f, 0.5f}, {1.5f, 1.5f, 3.0f, 0.5f}};
  EXPECT_EQ(spread_stain(cuts, 2, grid, 1, 1), 0.75f);
  EXPECT_EQ(spread_stain(cuts, 1, grid, 1, 1), 0.5f);
  EXPECT_EQ(spread_stain(cuts, 0, grid, 1, 1), 0.0f);
}

TEST(SpreadStain, StaysBelowOneHoweverManyFullCutsOverlap) {
  const PixelGrid grid{4, 4, 1.0f, 1.0f};
  std::vector<SpreadCut> cuts(50, SpreadCut{2.0f, 2.0f, 3.0f, 1.0f});
  const float stain = spread_stain(cuts.data(), 50, grid, 0, 0);
  EXPECT_GT(stain, 0.0f);
  EXPECT_LE(stain, 1.0f);
}

TEST(SpreadStain, MeasuresDistancesInMillimetresOnNonSquarePixels) {
  // Pixels 0.5 mm wide and 2 mm tall: pixel (5, 1) has its centre at (2.75, 3) mm.
  const PixelGrid grid{10, 4, 0.5f, 2.0f};
  const SpreadCut cut{2.75f, 3.0f, 1.0f, 1.0f};
  EXPECT_EQ(spread_stain(&cut, 1, grid, 5, 1), 1.0f);
  EXPECT_EQ(spread_stain(&cut, 1, grid, 5, 0), 0.0f);  // 2 mm up: outside the 1 mm radius
  EXPECT_GT(spread_stain(&cut, 1, grid, 6, 1), 0.0f);  // 0.5 mm right: inside
}

TEST(CutAmplitude, RampsLinearlyFromTheStartAndHoldsAtOne) {
  EXPECT_EQ(cut_amplitude(1.0, 0.5, 0.5), 0.0f);
  EXPECT_EQ(cut_amplitude(1.0, 0.5, 1.0), 0.0f);
  EXPECT_EQ(cut_amplitude(1.0, 0.5, 2.0), 0.5f);
  EXPECT_EQ(cut_amplitude(1.0, 0.5, 3.0), 1.0f);
  EXPECT_EQ(cut_amplitude(1.0, 0.5, 100.0), 1.0f);
}

}  // namespace
}  // namespace bleedsim
