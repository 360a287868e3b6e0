// The PNG writer (core/io/png_writer.h), read back with stb_image: exact bytes, nothing left beside
// the file, and a clear error where the folder is missing.
#include "core/io/png_writer.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cstdint>
#include <filesystem>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/io/hdf5_read_back.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;
using namespace test;

constexpr int kWidth = 7;
constexpr int kHeight = 5;
constexpr int kPixels = kWidth * kHeight;

// Every byte differs from its neighbours.
std::vector<std::uint8_t> pattern() {
  std::vector<std::uint8_t> rgba(std::size_t(kPixels) * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = std::uint8_t(i * 7 + 62);
  return rgba;
}

TEST(WritePngRgba, ReadsBackExactlyAndLeavesNoTemporary) {
  const fs::path folder = test_output_folder("png_writer");
  const fs::path path = folder / "frame_000000.png";
  const std::vector<std::uint8_t> rgba = pattern();
  write_png_rgba(path.string(), kWidth, kHeight, rgba.data());

  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &width, &height, &channels, 4);
  ASSERT_NE(pixels, nullptr) << stbi_failure_reason();
  const std::vector<std::uint8_t> read(pixels, pixels + std::size_t(kPixels) * 4);
  stbi_image_free(pixels);
  EXPECT_EQ(width, kWidth);
  EXPECT_EQ(height, kHeight);
  EXPECT_EQ(channels, 4);
  EXPECT_EQ(read, rgba);
  EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 1)
      << "something beside the PNG was left in " << folder;
}

// A full disk (issue 13, item 4): stb's own writer ignored fwrite's result and left a short PNG.
// Here the file is /dev/full, where every write fails with ENOSPC.
TEST(WritePngRgba, AFullDiskIsReportedWithTheOsErrorAndLeavesNothing) {
  const fs::path folder = test_output_folder("png_writer");
  const fs::path path = folder / "frame_000000.png";
  fs::create_symlink("/dev/full", folder / "frame_000000.png.tmp");
  const std::vector<std::uint8_t> rgba = pattern();
  try {
    write_png_rgba(path.string(), kWidth, kHeight, rgba.data());
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), "cannot write PNG '" + path.string() + "': No space left on device");
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(fs::symlink_status(folder / "frame_000000.png.tmp")));
}

TEST(WritePngRgba, MissingFolderThrowsAndLeavesNothing) {
  const fs::path folder = test_output_folder("png_writer");
  const fs::path path = folder / "png" / "frame_000000.png";
  const std::vector<std::uint8_t> rgba = pattern();
  try {
    write_png_rgba(path.string(), kWidth, kHeight, rgba.data());
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
  EXPECT_TRUE(fs::is_empty(folder));
}

}  // namespace
}  // namespace bleedsim
