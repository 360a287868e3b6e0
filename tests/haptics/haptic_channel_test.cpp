// The haptic channel in the HDF5 file (core/haptics/haptic_channel.h, Hdf5FrameWriter): /haptics grows
// by the ticks each frame brings, every column reads back as written, and a file made without the
// channel takes no ticks.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/haptics/haptics.h"
#include "core/io/hdf5_writer.h"
#include "tests/io/hdf5_read_back.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;
using namespace test;

// The frame alone, 2 × 1 px: what the channel is written beside.
const std::vector<FieldLayout> kFrameOnly = {{"frame", ElementType::u8, 4, 2, 1, "", "composited frame, RGBA8"}};
const std::uint8_t kPixels[8] = {10, 20, 30, 255, 40, 50, 60, 255};
const void* const kRgba = kPixels;

// Tick n of the sample: every column a different function of n.
HapticTick sample_tick(int n) {
  HapticTick t;
  t.tick = n;
  t.t_s = n / 1000.0;
  t.tool_m = Eigen::Vector3d(0.001 * n, -0.002, 0.12 - 0.0001 * n);
  t.panel_mm = Eigen::Vector2d(10.0 + n, 5.0);
  t.buttons = std::uint8_t(n % 16);
  t.contact = n % 2 == 1;
  t.penetration_m = t.contact ? 0.0001 * n : 0.0;
  t.force_N = Eigen::Vector3d(0, 0, 0.05 * n);
  t.cutting = n == 3;
  return t;
}

TEST(Hdf5FrameWriter, TheHapticChannelGrowsByEachFramesTicks) {
  const fs::path path = test_output_folder("haptic_channel") / "frames.h5";
  {
    Hdf5FrameWriter writer(path.string(), kFrameOnly, {}, 4, true);
    int n = 0;
    for (int frame = 0; frame < 3; ++frame) {
      std::vector<HapticTick> ticks;
      for (int i = 0; i < 2 + frame; ++i) ticks.push_back(sample_tick(n++));  // 2, 3, 4 ticks
      writer.append((frame + 1) / 30.0, {kRgba}, ticks);
    }
    writer.finish(true);
  }
  File file(path);
  const Extent force = extent_of(Dataset(file, "/haptics/force"));
  EXPECT_EQ(force.dims, (std::vector<hsize_t>{9, 3}));
  EXPECT_EQ(extent_of(Dataset(file, "/haptics/time")).dims, std::vector<hsize_t>{9});
  const std::vector<double> time = read_all<double>(Dataset(file, "/haptics/time"), H5T_NATIVE_DOUBLE);
  const std::vector<double> forces = read_all<double>(Dataset(file, "/haptics/force"), H5T_NATIVE_DOUBLE);
  const std::vector<double> panel = read_all<double>(Dataset(file, "/haptics/panel_position"), H5T_NATIVE_DOUBLE);
  const std::vector<std::uint8_t> contact = read_all<std::uint8_t>(Dataset(file, "/haptics/contact"), H5T_NATIVE_UINT8);
  const std::vector<std::uint8_t> buttons = read_all<std::uint8_t>(Dataset(file, "/haptics/buttons"), H5T_NATIVE_UINT8);
  for (int n = 0; n < 9; ++n) {
    SCOPED_TRACE("tick " + std::to_string(n));
    const HapticTick t = sample_tick(n);
    EXPECT_EQ(time[std::size_t(n)], t.t_s);
    EXPECT_EQ(forces[std::size_t(3 * n + 2)], t.force_N.z());
    EXPECT_EQ(panel[std::size_t(2 * n)], t.panel_mm.x());
    EXPECT_EQ(contact[std::size_t(n)], t.contact ? 1 : 0);
    EXPECT_EQ(buttons[std::size_t(n)], t.buttons);
  }
}

TEST(Hdf5FrameWriter, WithoutTheHapticChannelTicksAreRefused) {
  const fs::path path = test_output_folder("haptic_channel") / "frames.h5";
  Hdf5FrameWriter writer(path.string(), kFrameOnly, {}, 4);
  EXPECT_THROW(writer.append(1 / 30.0, {kRgba}, {sample_tick(0)}), std::invalid_argument);
  writer.append(1 / 30.0, {kRgba});
  writer.finish(true);
  File file(path);
  EXPECT_LE(H5Lexists(file, "haptics", H5P_DEFAULT), 0);
}

}  // namespace
}  // namespace bleedsim
