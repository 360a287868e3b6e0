// Compositing the stain over the tissue (core/physics/blend.h).
#include <gtest/gtest.h>

#include <cmath>

#include "core/physics/blend.h"

namespace bleedsim {
namespace {

TEST(ByteConversion, EveryByteSurvivesTheRoundTrip) {
  for (int v = 0; v < 256; ++v)
    EXPECT_EQ(byte_from_unit(unit_from_byte(std::uint8_t(v))), v) << "byte " << v;
}

TEST(ByteConversion, ClampsOutOfRangeAndNotANumber) {
  EXPECT_EQ(byte_from_unit(-0.3f), 0);
  EXPECT_EQ(byte_from_unit(1.7f), 255);
  EXPECT_EQ(byte_from_unit(NAN), 0);
  EXPECT_EQ(byte_from_unit(0.5f), 128);  // 127.5 rounds half up
}

TEST(BlendPixel, WithoutStainShowsTheTissue) {
  const std::uint8_t tissue[4] = {204, 115, 110, 255};
  std::uint8_t frame[4];
  blend_pixel(tissue, 0.0f, 0.0f, nullptr, frame);
  EXPECT_EQ(std::vector<int>(frame, frame + 4), std::vector<int>({204, 115, 110, 255}));
}

TEST(BlendPixel, TakesTheStainOutOfGreenAndBlueSoItReadsRed) {
  const std::uint8_t tissue[4] = {204, 153, 102, 255};  // green 0.6, blue 0.4
  std::uint8_t frame[4];
  blend_pixel(tissue, 0.2f, 0.0f, nullptr, frame);
  EXPECT_EQ(std::vector<int>(frame, frame + 4), std::vector<int>({204, 102, 51, 255}));
  blend_pixel(tissue, 1.0f, 0.0f, nullptr, frame);
  EXPECT_EQ(std::vector<int>(frame, frame + 4), std::vector<int>({204, 0, 0, 255}));
}

}  // namespace
}  // namespace bleedsim
