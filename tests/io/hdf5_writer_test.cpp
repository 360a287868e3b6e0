// The HDF5 frame writer, read back through the HDF5 C API: the layout docs/output-format.md
// promises, the bytes written, determinism and partial files (the frames it writes:
// hdf5_samples.h; the layout checker against them: hdf5_layout_checker_test.cpp).
#include "core/io/hdf5_writer.h"
#include "tests/io/hdf5_read_back.h"
#include "tests/io/hdf5_samples.h"
#include "tests/test_paths.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bleedsim {
namespace {

namespace fs = std::filesystem;
using namespace test;

fs::path partial(const fs::path& path) { return path.string() + ".partial"; }

std::vector<char> file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <class T>
std::vector<T> frame_of(const std::vector<T>& all, int frame, std::size_t frame_size) {
  const auto begin = all.begin() + std::ptrdiff_t(std::size_t(frame) * frame_size);
  return {begin, begin + std::ptrdiff_t(frame_size)};
}

std::string message_of(const std::exception& error) { return error.what(); }

// --- The layout ----------------------------------------------------------------------------------

TEST(Hdf5FrameWriter, PartialFileUntilFinishThenFinalName) {
  const fs::path path = test_folder() / "frames.h5";
  Hdf5FrameWriter writer(path.string(), sample_fields(), kAttributes, 4);
  append_sample_frame(writer, 0);
  EXPECT_TRUE(fs::exists(partial(path)));
  EXPECT_FALSE(fs::exists(path));
  writer.finish(true);
  EXPECT_FALSE(fs::exists(partial(path)));
  EXPECT_TRUE(fs::exists(path));
  EXPECT_EQ(writer.frames_written(), 1);
}

TEST(Hdf5FrameWriter, ShapesChunksAndTypes) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 4);
  File file(path);
  Dataset frame(file, "/frame");
  Dataset stain(file, "/spread/stain");

  EXPECT_EQ(dims_of(frame), (std::vector<hsize_t>{kFrames, kHeight, kWidth, 4}));
  EXPECT_EQ(dims_of(stain), (std::vector<hsize_t>{kFrames, kHeight, kWidth}));
  EXPECT_EQ(extent_of(frame).max_dims, (std::vector<hsize_t>{H5S_UNLIMITED, kHeight, kWidth, 4}));
  EXPECT_EQ(extent_of(stain).max_dims, (std::vector<hsize_t>{H5S_UNLIMITED, kHeight, kWidth}));
  EXPECT_EQ(chunk_of(frame), (std::vector<hsize_t>{1, kHeight, kWidth, 4}));
  EXPECT_EQ(chunk_of(stain), (std::vector<hsize_t>{1, kHeight, kWidth}));

  Type frame_type(H5Dget_type(frame));
  Type stain_type(H5Dget_type(stain));
  EXPECT_GT(H5Tequal(frame_type, H5T_STD_U8LE), 0);
  EXPECT_GT(H5Tequal(stain_type, H5T_IEEE_F32LE), 0);
}

TEST(Hdf5FrameWriter, ShuffleThenDeflateWhenLevelAboveZero) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 4);
  File file(path);
  const std::vector<H5Z_filter_t> expected = {H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE};
  EXPECT_EQ(filters_of(Dataset(file, "/frame")), expected);
  EXPECT_EQ(filters_of(Dataset(file, "/spread/stain")), expected);
}

TEST(Hdf5FrameWriter, NoFiltersAtLevelZero) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 0);
  File file(path);
  EXPECT_TRUE(filters_of(Dataset(file, "/frame")).empty());
  EXPECT_TRUE(filters_of(Dataset(file, "/spread/stain")).empty());
  // Unfiltered data reads back just the same.
  const std::vector<float> stain =
      read_all<float>(Dataset(file, "/spread/stain"), H5T_NATIVE_FLOAT);
  EXPECT_EQ(frame_of(stain, kFrames - 1, kPixels), stain_values(kFrames - 1));
}

TEST(Hdf5FrameWriter, DataReadsBackFrameByFrame) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 4);
  File file(path);
  const std::vector<std::uint8_t> rgba =
      read_all<std::uint8_t>(Dataset(file, "/frame"), H5T_NATIVE_UINT8);
  const std::vector<float> stain =
      read_all<float>(Dataset(file, "/spread/stain"), H5T_NATIVE_FLOAT);
  for (int frame = 0; frame < kFrames; ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    EXPECT_EQ(frame_of(rgba, frame, kPixels * 4), frame_pattern(frame));
    EXPECT_EQ(frame_of(stain, frame, kPixels), stain_values(frame));
  }
}

TEST(Hdf5FrameWriter, TimeDatasetHoldsFrameTimesInSeconds) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 4);
  File file(path);
  Dataset time(file, "/time");
  EXPECT_EQ(dims_of(time), (std::vector<hsize_t>{kFrames}));
  EXPECT_EQ(extent_of(time).max_dims, (std::vector<hsize_t>{H5S_UNLIMITED}));
  Type type(H5Dget_type(time));
  EXPECT_GT(H5Tequal(type, H5T_IEEE_F64LE), 0);
  EXPECT_EQ(read_all<double>(time, H5T_NATIVE_DOUBLE),
            (std::vector<double>{frame_time(0), frame_time(1), frame_time(2)}));
  EXPECT_EQ(text_attribute(time, "unit").value, "s");
  EXPECT_EQ(text_attribute(time, "description").value,
            "simulated time of each frame (end of its frame period)");
}

TEST(Hdf5FrameWriter, RootAttributesAsUtf8TextPlusCompletion) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 4);
  File file(path);
  for (const auto& [name, value] : kAttributes) {
    SCOPED_TRACE(name);
    const Text text = text_attribute(file, name.c_str());
    EXPECT_EQ(text.value, value);
    EXPECT_TRUE(text.variable_length);
    EXPECT_EQ(text.cset, H5T_CSET_UTF8);
  }
  EXPECT_EQ(scalar_attribute<std::int8_t>(file, "complete", H5T_NATIVE_INT8), 1);
  EXPECT_EQ(scalar_attribute<std::int64_t>(file, "frames_written", H5T_NATIVE_INT64), kFrames);
}

TEST(Hdf5FrameWriter, FieldUnitAndDescription) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 4);
  File file(path);
  Dataset stain(file, "/spread/stain");
  EXPECT_EQ(text_attribute(stain, "unit").value, "1");
  EXPECT_EQ(text_attribute(stain, "description").value, "stain coverage");
  EXPECT_EQ(text_attribute(Dataset(file, "/frame"), "unit").value, "");
}

TEST(Hdf5FrameWriter, ImageAttributesFollowTheHdf5ImageSpec) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 4);
  File file(path);
  Dataset frame(file, "/frame");
  Dataset stain(file, "/spread/stain");

  const Text frame_class = text_attribute(frame, "CLASS");
  EXPECT_EQ(frame_class.value, "IMAGE");
  EXPECT_FALSE(frame_class.variable_length);  // the spec's fixed-length, null-terminated ASCII
  EXPECT_EQ(frame_class.cset, H5T_CSET_ASCII);
  EXPECT_EQ(frame_class.padding, H5T_STR_NULLTERM);
  EXPECT_EQ(text_attribute(frame, "IMAGE_VERSION").value, "1.2");
  EXPECT_EQ(text_attribute(frame, "IMAGE_SUBCLASS").value, "IMAGE_TRUECOLOR");
  EXPECT_EQ(text_attribute(frame, "INTERLACE_MODE").value, "INTERLACE_PIXEL");

  EXPECT_EQ(text_attribute(stain, "CLASS").value, "IMAGE");
  EXPECT_EQ(text_attribute(stain, "IMAGE_SUBCLASS").value, "IMAGE_GRAYSCALE");
  EXPECT_EQ(scalar_attribute<std::uint8_t>(stain, "IMAGE_WHITE_IS_ZERO", H5T_NATIVE_UINT8), 0);
  EXPECT_EQ(H5Aexists(stain, "INTERLACE_MODE"), 0);
}

// --- Per-element arrays ---------------------------------------------------------------------------

TEST(Hdf5FrameWriter, NonImageFieldsAreTimeSeriesOfElements) {
  const fs::path path = test_folder() / "frames.h5";
  write_array_sample(path, 4);
  File file(path);
  Dataset position(file, "/particles/position");
  Dataset accounting(file, "/particles/accounting");
  Dataset ids(file, "/particles/id");

  // (T, N, C) and (T, N): no height axis.
  EXPECT_EQ(dims_of(position), (std::vector<hsize_t>{kFrames, kSlots, 2}));
  EXPECT_EQ(dims_of(accounting), (std::vector<hsize_t>{kFrames, kCounters}));
  EXPECT_EQ(dims_of(ids), (std::vector<hsize_t>{kFrames, kSlots}));
  EXPECT_EQ(extent_of(position).max_dims, (std::vector<hsize_t>{H5S_UNLIMITED, kSlots, 2}));
  EXPECT_EQ(extent_of(accounting).max_dims, (std::vector<hsize_t>{H5S_UNLIMITED, kCounters}));
  EXPECT_EQ(chunk_of(position), (std::vector<hsize_t>{1, kSlots, 2}));
  EXPECT_EQ(chunk_of(accounting), (std::vector<hsize_t>{1, kCounters}));
  EXPECT_EQ(chunk_of(ids), (std::vector<hsize_t>{1, kSlots}));

  Type position_type(H5Dget_type(position));
  Type accounting_type(H5Dget_type(accounting));
  Type id_type(H5Dget_type(ids));
  EXPECT_GT(H5Tequal(position_type, H5T_IEEE_F32LE), 0);
  EXPECT_GT(H5Tequal(accounting_type, H5T_STD_U64LE), 0);
  EXPECT_GT(H5Tequal(id_type, H5T_STD_U32LE), 0);

  const std::vector<H5Z_filter_t> expected = {H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE};
  EXPECT_EQ(filters_of(position), expected);
  EXPECT_EQ(filters_of(accounting), expected);
  EXPECT_EQ(filters_of(ids), expected);

  // The images beside them keep their (T, H, W[, C]) shape.
  EXPECT_EQ(dims_of(Dataset(file, "/frame")), (std::vector<hsize_t>{kFrames, kHeight, kWidth, 4}));
  EXPECT_EQ(dims_of(Dataset(file, "/spread/stain")),
            (std::vector<hsize_t>{kFrames, kHeight, kWidth}));
}

TEST(Hdf5FrameWriter, NonImageFieldsReadBackExactly) {
  for (const int level : {0, 4}) {
    SCOPED_TRACE("deflate level " + std::to_string(level));
    const fs::path path = test_folder() / ("frames" + std::to_string(level) + ".h5");
    write_array_sample(path, level);
    File file(path);
    const std::vector<float> position =
        read_all<float>(Dataset(file, "/particles/position"), H5T_NATIVE_FLOAT);
    const std::vector<std::uint64_t> accounting =
        read_all<std::uint64_t>(Dataset(file, "/particles/accounting"), H5T_NATIVE_UINT64);
    const std::vector<std::uint32_t> ids =
        read_all<std::uint32_t>(Dataset(file, "/particles/id"), H5T_NATIVE_UINT32);
    const std::vector<std::uint8_t> rgba =
        read_all<std::uint8_t>(Dataset(file, "/frame"), H5T_NATIVE_UINT8);
    ASSERT_EQ(position.size(), std::size_t(kFrames) * kSlots * 2);
    ASSERT_EQ(accounting.size(), std::size_t(kFrames) * kCounters);
    ASSERT_EQ(ids.size(), std::size_t(kFrames) * kSlots);
    for (int frame = 0; frame < kFrames; ++frame) {
      SCOPED_TRACE("frame " + std::to_string(frame));
      EXPECT_EQ(frame_of(position, frame, kSlots * 2), position_values(frame));
      EXPECT_EQ(frame_of(accounting, frame, kCounters), accounting_values(frame));
      EXPECT_EQ(frame_of(ids, frame, kSlots), id_values(frame));
      EXPECT_EQ(frame_of(rgba, frame, kPixels * 4), frame_pattern(frame));
    }
  }
}

TEST(Hdf5FrameWriter, NonImageFieldsHaveUnitsButNoImageAttributes) {
  const fs::path path = test_folder() / "frames.h5";
  write_array_sample(path, 4);
  File file(path);
  for (const char* name : {"/particles/position", "/particles/accounting", "/particles/id"}) {
    SCOPED_TRACE(name);
    Dataset dataset(file, name);
    for (const char* image_attribute : {"CLASS", "IMAGE_VERSION", "IMAGE_SUBCLASS",
                                        "INTERLACE_MODE", "IMAGE_WHITE_IS_ZERO"})
      EXPECT_EQ(H5Aexists(dataset, image_attribute), 0) << image_attribute;
    EXPECT_TRUE(text_attribute(dataset, "unit").variable_length);
  }
  Dataset position(file, "/particles/position");
  EXPECT_EQ(text_attribute(position, "unit").value, "m");
  EXPECT_EQ(text_attribute(position, "description").value,
            "particle position (x, y), one per ring-buffer slot");
  Dataset accounting(file, "/particles/accounting");
  EXPECT_EQ(text_attribute(accounting, "unit").value, "1");
  EXPECT_EQ(text_attribute(accounting, "description").value, "particle counters");
  EXPECT_EQ(text_attribute(Dataset(file, "/particles/id"), "unit").value, "");
  // The images in the same file still are images.
  EXPECT_EQ(text_attribute(Dataset(file, "/frame"), "CLASS").value, "IMAGE");
  EXPECT_EQ(text_attribute(Dataset(file, "/spread/stain"), "CLASS").value, "IMAGE");
}

TEST(Hdf5FrameWriter, NonImageFieldWithHeightOtherThanOneIsRefused) {
  const fs::path path = test_folder() / "frames.h5";
  for (const int height : {2, kHeight}) {
    SCOPED_TRACE("height " + std::to_string(height));
    std::vector<FieldLayout> fields = sample_fields();
    fields.push_back({"particles/position", ElementType::f32, 2, kSlots, height, "m",
                      "particle position", false});
    try {
      Hdf5FrameWriter writer(path.string(), fields, kAttributes, 4);
      ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(message_of(error).find("particles/position"), std::string::npos) << error.what();
      EXPECT_NE(message_of(error).find("height"), std::string::npos) << error.what();
    }
    EXPECT_FALSE(fs::exists(partial(path)));
  }
  // The same layout as an image is fine.
  std::vector<FieldLayout> fields = sample_fields();
  fields.push_back({"spread/velocity", ElementType::f32, 2, kWidth, kHeight, "m/s", "velocity"});
  EXPECT_NO_THROW(Hdf5FrameWriter(path.string(), fields, kAttributes, 4));
}

// Each object's name, and whether its header carries any time. (H5Pget_obj_track_times on a
// dataset's creation list read back says nothing: HDF5 1.10 reports 1 there whatever was written.)
herr_t collect_object_times(hid_t, const char* name, const H5O_info_t* info, void* out) {
  const bool timed = info->atime || info->mtime || info->ctime || info->btime;
  static_cast<std::vector<std::pair<std::string, bool>>*>(out)->emplace_back(name, timed);
  return 0;
}

TEST(Hdf5FrameWriter, NoObjectTimeTracking) {
  const fs::path path = test_folder() / "frames.h5";
  write_sample(path, 4);
  File file(path);
  std::vector<std::pair<std::string, bool>> objects;
  ASSERT_GE(
      H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, collect_object_times, &objects, H5O_INFO_TIME),
      0);
  const std::vector<std::pair<std::string, bool>> untimed = {
      {".", false}, {"frame", false}, {"spread", false}, {"spread/stain", false}, {"time", false}};
  EXPECT_EQ(objects, untimed);
}

TEST(Hdf5FrameWriter, IdenticalInputsGiveIdenticalBytes) {
  const fs::path folder = test_folder();
  write_sample(folder / "a.h5", 4);
  write_sample(folder / "b.h5", 4);
  const std::vector<char> a = file_bytes(folder / "a.h5");
  const std::vector<char> b = file_bytes(folder / "b.h5");
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(a.size(), b.size());
  const auto [in_a, in_b] = std::mismatch(a.begin(), a.end(), b.begin());
  EXPECT_TRUE(in_a == a.end()) << "first differing byte at offset " << (in_a - a.begin());
}

// --- Partial and interrupted runs ----------------------------------------------------------------

TEST(Hdf5FrameWriter, UnfinishedWriterLeavesReadablePartial) {
  const fs::path path = test_folder() / "frames.h5";
  {
    Hdf5FrameWriter writer(path.string(), sample_fields(), kAttributes, 4);
    append_sample_frame(writer, 0);
    append_sample_frame(writer, 1);
  }  // unwound without finish()
  EXPECT_FALSE(fs::exists(path));
  ASSERT_TRUE(fs::exists(partial(path)));

  File file(partial(path));
  EXPECT_EQ(scalar_attribute<std::int8_t>(file, "complete", H5T_NATIVE_INT8), 0);
  EXPECT_EQ(scalar_attribute<std::int64_t>(file, "frames_written", H5T_NATIVE_INT64), 2);
  const std::vector<float> stain =
      read_all<float>(Dataset(file, "/spread/stain"), H5T_NATIVE_FLOAT);
  EXPECT_EQ(stain.size(), 2u * kPixels);
  EXPECT_EQ(frame_of(stain, 1, kPixels), stain_values(1));
}

// A copy of the .partial taken while the writer is still open is what a hard kill (SIGKILL, power
// loss) would leave on disk: every appended frame must already be there.
TEST(Hdf5FrameWriter, EveryAppendedFrameIsOnDiskBeforeTheNext) {
  const fs::path folder = test_folder();
  const fs::path path = folder / "frames.h5";
  const fs::path killed = folder / "killed.h5";
  Hdf5FrameWriter writer(path.string(), sample_fields(), kAttributes, 4);
  append_sample_frame(writer, 0);
  append_sample_frame(writer, 1);
  fs::copy_file(partial(path), killed);

  File file(killed);
  EXPECT_EQ(scalar_attribute<std::int8_t>(file, "complete", H5T_NATIVE_INT8), 0);
  EXPECT_EQ(scalar_attribute<std::int64_t>(file, "frames_written", H5T_NATIVE_INT64), 2);
  const std::vector<std::uint8_t> rgba =
      read_all<std::uint8_t>(Dataset(file, "/frame"), H5T_NATIVE_UINT8);
  ASSERT_EQ(rgba.size(), 2u * kPixels * 4);
  EXPECT_EQ(frame_of(rgba, 1, kPixels * 4), frame_pattern(1));
}

TEST(Hdf5FrameWriter, FinishIncompleteStillTakesTheFinalName) {
  const fs::path path = test_folder() / "frames.h5";
  Hdf5FrameWriter writer(path.string(), sample_fields(), kAttributes, 4);
  append_sample_frame(writer, 0);
  writer.finish(false);
  EXPECT_FALSE(fs::exists(partial(path)));
  File file(path);
  EXPECT_EQ(scalar_attribute<std::int8_t>(file, "complete", H5T_NATIVE_INT8), 0);
  EXPECT_EQ(scalar_attribute<std::int64_t>(file, "frames_written", H5T_NATIVE_INT64), 1);
}

TEST(Hdf5FrameWriter, FinishReplacesAnOldFile) {
  const fs::path path = test_folder() / "frames.h5";
  std::ofstream(path) << "an older run";
  write_sample(path, 4);
  File file(path);
  EXPECT_EQ(scalar_attribute<std::int64_t>(file, "frames_written", H5T_NATIVE_INT64), kFrames);
}

// --- Errors --------------------------------------------------------------------------------------

TEST(Hdf5FrameWriter, MissingFolderThrowsNamingThePath) {
  const fs::path path = test_folder() / "no_such_folder" / "frames.h5";
  try {
    Hdf5FrameWriter writer(path.string(), sample_fields(), kAttributes, 4);
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(message_of(error).find(path.string()), std::string::npos) << error.what();
  }
}

// A write failure (issue 13, item 4) names the file and the OS error in one line: HDF5's own text
// ran over two lines and said "bytes actually written = 18446744073709551615". Here the file is
// /dev/full, where every write fails with ENOSPC.
TEST(Hdf5FrameWriter, AWriteFailureNamesTheFileAndTheOsErrorInOneLine) {
  const fs::path path = test_folder() / "frames.h5";
  fs::create_symlink("/dev/full", path.string() + ".partial");
  try {
    Hdf5FrameWriter writer(path.string(), sample_fields(), kAttributes, 4);
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    const std::string what = error.what();
    EXPECT_EQ(what.rfind("cannot ", 0), 0u) << what;
    EXPECT_NE(what.find("HDF5 file '" + path.string() + ".partial': No space left on device"), std::string::npos)
        << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(Hdf5FrameWriter, WrongPointerCountIsInvalidArgument) {
  const fs::path path = test_folder() / "frames.h5";
  Hdf5FrameWriter writer(path.string(), sample_fields(), kAttributes, 4);
  const std::vector<std::uint8_t> rgba = frame_pattern(0);
  EXPECT_THROW(writer.append(frame_time(0), {rgba.data()}), std::invalid_argument);
  EXPECT_EQ(writer.frames_written(), 0);
}

TEST(Hdf5FrameWriter, AppendOrFinishAfterFinishIsLogicError) {
  const fs::path path = test_folder() / "frames.h5";
  Hdf5FrameWriter writer(path.string(), sample_fields(), kAttributes, 4);
  writer.finish(true);
  const std::vector<std::uint8_t> rgba = frame_pattern(0);
  const std::vector<float> stain = stain_values(0);
  EXPECT_THROW(writer.append(frame_time(0), {rgba.data(), stain.data()}), std::logic_error);
  EXPECT_THROW(writer.finish(true), std::logic_error);
}

TEST(Hdf5FrameWriter, FrameLargerThanAChunkCanHoldIsRefused) {
  const fs::path path = test_folder() / "frames.h5";
  const std::vector<FieldLayout> huge = {
      {"frame", ElementType::u8, 4, 65536, 16384, "", "one frame of exactly 4 GiB"}};
  EXPECT_THROW(Hdf5FrameWriter(path.string(), huge, kAttributes, 4), std::runtime_error);
  EXPECT_FALSE(fs::exists(partial(path)));
}

// No HDF5 object stays open once a writer is gone: finished, unfinished, or failed half-way.
TEST(Hdf5FrameWriter, ReleasesEveryHandle) {
  const fs::path folder = test_folder();
  write_sample(folder / "finished.h5", 4);
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);
  {
    Hdf5FrameWriter writer((folder / "unfinished.h5").string(), sample_fields(), kAttributes, 4);
    append_sample_frame(writer, 0);
  }
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);

  // /time is a dataset, so HDF5 itself refuses to open it as a group, after the file was made.
  const std::vector<FieldLayout> under_time = {
      {"time/stain", ElementType::f32, 1, kWidth, kHeight, "1", "cannot live under /time"}};
  try {
    Hdf5FrameWriter writer((folder / "failed.h5").string(), under_time, kAttributes, 4);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(message_of(error).find("/time"), std::string::npos) << error.what();
    EXPECT_NE(message_of(error).find("failed.h5.partial"), std::string::npos) << error.what();
  }
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);
}

}  // namespace
}  // namespace bleedsim
