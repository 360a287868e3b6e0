#include "core/io/contact_sheet.h"

#include <gtest/gtest.h>

#include <vector>

namespace bleedsim {
namespace {

TEST(ContactSheet, ShowsTheFirstTheLastAndEvenlyBetween) {
  const ContactSheet sheet(120, 4, 640, 480);
  for (long k : {0L, 40L, 79L, 119L}) EXPECT_TRUE(sheet.wants(k)) << k;  // round(i · 119 / 3)
  EXPECT_FALSE(sheet.wants(1));
  EXPECT_FALSE(sheet.wants(80));
  const ContactSheet fewer_frames(3, 10, 8, 8);  // more cells asked for than frames: every frame once
  for (long k : {0L, 1L, 2L}) EXPECT_TRUE(fewer_frames.wants(k));
}

TEST(ContactSheet, LaysOutShrunkFramesInAGridWithGutters) {
  // 700 px wide frames shrink by 3 (to at most 320 px): 234 × 67 thumbnails, 3 columns, 2 rows.
  const ContactSheet sheet(10, 5, 700, 200);
  EXPECT_EQ(sheet.thumb_width(), 234);
  EXPECT_EQ(sheet.thumb_height(), 67);
  EXPECT_EQ(sheet.width(), 3 * 234 + 4 * ContactSheet::kGutter);
  EXPECT_EQ(sheet.height(), 2 * 67 + 3 * ContactSheet::kGutter);
}

TEST(ContactSheet, EachThumbnailPixelIsItsBlocksMean) {
  // A 644 × 2 frame shrinks by 3, so its first thumbnail pixel, just past the gutter, is the mean
  // of the first 3 × 2 frame pixels.
  std::vector<std::uint8_t> frame(644 * 2 * 4, 0);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) frame[(y * 644 + x) * 4] = std::uint8_t(10 * (y * 3 + x));  // 0..50
  ContactSheet sheet(1, 1, 644, 2);
  sheet.add(0, frame.data());
  const int g = ContactSheet::kGutter;
  const std::uint8_t* first = &sheet.rgba()[(std::size_t(g) * sheet.width() + g) * 4];
  EXPECT_EQ(first[0], 25);  // (0 + 10 + 20 + 30 + 40 + 50) / 6
  EXPECT_EQ(sheet.rgba()[0], 32);  // the gutter
  // The last column holds 644 − 3·214 = 2 frame pixels per row: the mean of those alone.
  EXPECT_EQ(sheet.thumb_width(), 215);
}

}  // namespace
}  // namespace bleedsim
