// Frames filtered outside HDF5 (core/io/hdf5_filters.h) and stored with H5Dwrite_chunk, against the
// same frames written as before, through H5Dwrite into datasets that declare shuffle and deflate so
// that HDF5 runs its own filters: every chunk's stored bytes and filter mask (H5Dread_chunk) and every
// dataset's decoded data must be the same, for each element type, at deflate levels 0, 1, 4 and 9,
// for smooth frames and for random bytes that deflate makes larger.
#include "core/io/hdf5_filters.h"
#include "core/io/hdf5_writer.h"
#include "tests/io/hdf5_read_back.h"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace bleedsim {
namespace {

namespace fs = std::filesystem;
using namespace test;

using Bytes = std::vector<std::uint8_t>;

// One of each kind a run writes: the RGBA8 frame (1-byte elements: shuffle leaves them), a float32
// image, a 2-component float32 array, 64- and 32-bit counters, and a field of one element per frame.
std::vector<FieldLayout> fields() {
  return {{"frame", ElementType::u8, 4, 96, 64, "", "RGBA8"},
          {"spread/stain", ElementType::f32, 1, 96, 64, "1", "stain"},
          {"particles/position", ElementType::f32, 2, 1000, 1, "m", "positions", false},
          {"particles/accounting", ElementType::u64, 1, 6, 1, "1", "counters", false},
          {"particles/id", ElementType::u32, 1, 1000, 1, "", "ids", false},
          {"one", ElementType::f32, 1, 1, 1, "1", "a single value", false}};
}

constexpr int kFrames = 4;

std::uint64_t splitmix(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Frames 0-2 smooth, as a scene's fields are (deflate shrinks them); frame 3 random bytes, which
// deflate cannot shrink.
Bytes frame_of(const FieldLayout& field, int frame) {
  Bytes bytes(field.bytes());
  std::uint64_t state = std::uint64_t(frame) * 1000003u + field.bytes();
  if (frame == kFrames - 1) {
    for (std::uint8_t& b : bytes) b = std::uint8_t(splitmix(state));
    return bytes;
  }
  const std::size_t size = element_size(field.type), count = bytes.size() / size;
  for (std::size_t i = 0; i < count; ++i) {
    const double smooth = double(i % 97) * 0.25 + double(i / 97) * 0.5 + frame;
    std::uint8_t* at = bytes.data() + i * size;
    if (field.type == ElementType::f32) {
      const float value = float(smooth);
      std::memcpy(at, &value, size);
    } else if (field.type == ElementType::u64) {
      const std::uint64_t value = (std::uint64_t(1) << 40) + std::uint64_t(smooth * 8);
      std::memcpy(at, &value, size);
    } else if (field.type == ElementType::u32) {
      const std::uint32_t value = 0xF0000000u + std::uint32_t(i) * 7u + std::uint32_t(frame);
      std::memcpy(at, &value, size);
    } else {
      *at = std::uint8_t(smooth);
    }
  }
  return bytes;
}

hid_t stored_type(ElementType type) {
  switch (type) {
    case ElementType::u8: return H5T_STD_U8LE;
    case ElementType::u32: return H5T_STD_U32LE;
    case ElementType::u64: return H5T_STD_U64LE;
    case ElementType::f32: return H5T_IEEE_F32LE;
  }
  return H5I_INVALID_HID;
}

hid_t memory_type(ElementType type) {
  switch (type) {
    case ElementType::u8: return H5T_NATIVE_UINT8;
    case ElementType::u32: return H5T_NATIVE_UINT32;
    case ElementType::u64: return H5T_NATIVE_UINT64;
    case ElementType::f32: return H5T_NATIVE_FLOAT;
  }
  return H5I_INVALID_HID;
}

// (1, H, W[, C]) for an image, (1, N[, C]) for an array, as docs/output-format.md lays them out.
std::vector<hsize_t> frame_shape(const FieldLayout& field) {
  std::vector<hsize_t> shape = {1};
  if (field.image) shape.push_back(hsize_t(field.height));
  shape.push_back(hsize_t(field.width));
  if (field.channels != 1) shape.push_back(hsize_t(field.channels));
  return shape;
}

// The path the writer took before: each frame through H5Dwrite, HDF5 running the filters the
// dataset declares (shuffle then deflate at the level; none at level 0).
void write_through_hdf5_filters(const fs::path& path, int level) {
  Owned<H5Fclose> file(checked(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create"));
  Plist lcpl(checked(H5Pcreate(H5P_LINK_CREATE), "lcpl"));
  checked_status(H5Pset_create_intermediate_group(lcpl, 1), "intermediate groups");
  for (const FieldLayout& field : fields()) {
    std::vector<hsize_t> dims = frame_shape(field), max_dims = dims, chunk = dims;
    dims[0] = 0;
    max_dims[0] = H5S_UNLIMITED;
    Space space(checked(H5Screate_simple(int(dims.size()), dims.data(), max_dims.data()), "space"));
    Plist dcpl(checked(H5Pcreate(H5P_DATASET_CREATE), "dcpl"));
    checked_status(H5Pset_chunk(dcpl, int(chunk.size()), chunk.data()), "chunk");
    if (level > 0) {
      checked_status(H5Pset_shuffle(dcpl), "shuffle");
      checked_status(H5Pset_deflate(dcpl, unsigned(level)), "deflate");
    }
    Owned<H5Dclose> dataset(checked(
        H5Dcreate2(file, field.name.c_str(), stored_type(field.type), space, lcpl, dcpl, H5P_DEFAULT),
        "create " + field.name));
    for (int frame = 0; frame < kFrames; ++frame) {
      std::vector<hsize_t> grown = frame_shape(field), start(grown.size(), 0), count = frame_shape(field);
      grown[0] = hsize_t(frame) + 1;
      start[0] = hsize_t(frame);
      checked_status(H5Dset_extent(dataset, grown.data()), "extend");
      Space file_space(checked(H5Dget_space(dataset), "file space"));
      checked_status(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
                     "select");
      Space memory_space(checked(H5Screate_simple(int(count.size()), count.data(), nullptr), "memory space"));
      const Bytes bytes = frame_of(field, frame);
      checked_status(H5Dwrite(dataset, memory_type(field.type), memory_space, file_space, H5P_DEFAULT, bytes.data()),
                     "write " + field.name);
    }
  }
}

// The path the writer takes now: each field's chunk filtered by filter() (as a run's workers do),
// then stored as it is.
void write_filtered_chunks(const fs::path& path, int level) {
  Hdf5FrameWriter writer(path.string(), fields(), {}, level);
  for (int frame = 0; frame < kFrames; ++frame) {
    std::vector<Bytes> chunks(fields().size());
    for (std::size_t f = 0; f < chunks.size(); ++f) writer.filter(f, frame_of(fields()[f], frame).data(), chunks[f]);
    writer.append_chunks((frame + 1) / 30.0, chunks);
  }
  writer.finish(true);
}

struct StoredChunk {
  std::uint32_t filter_mask = 0;
  Bytes bytes;
};

StoredChunk stored_chunk(hid_t dataset, const FieldLayout& field, int frame) {
  std::vector<hsize_t> offset(frame_shape(field).size(), 0);
  offset[0] = hsize_t(frame);
  hsize_t size = 0;
  checked_status(H5Dget_chunk_storage_size(dataset, offset.data(), &size), "chunk size");
  StoredChunk chunk;
  chunk.bytes.resize(std::size_t(size));
  checked_status(H5Dread_chunk(dataset, H5P_DEFAULT, offset.data(), &chunk.filter_mask, chunk.bytes.data()),
                 "read chunk");
  return chunk;
}

Bytes decoded(hid_t dataset, const FieldLayout& field) {
  Bytes bytes(field.bytes() * kFrames);
  checked_status(H5Dread(dataset, memory_type(field.type), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), "read");
  return bytes;
}

class Hdf5Filters : public testing::TestWithParam<int> {};

TEST_P(Hdf5Filters, FilteredChunksAreTheBytesHdf5sOwnFiltersStore) {
  const int level = GetParam();
  const fs::path folder = test_output_folder("hdf5_filters");
  write_through_hdf5_filters(folder / "hdf5_filters.h5", level);
  write_filtered_chunks(folder / "direct.h5", level);
  File reference(folder / "hdf5_filters.h5"), direct(folder / "direct.h5");
  for (const FieldLayout& field : fields()) {
    Dataset a(reference, "/" + field.name), b(direct, "/" + field.name);
    EXPECT_EQ(filters_of(a), filters_of(b)) << field.name;
    Bytes expected;
    for (int frame = 0; frame < kFrames; ++frame) {
      const StoredChunk by_hdf5 = stored_chunk(a, field, frame), filtered = stored_chunk(b, field, frame);
      EXPECT_EQ(filtered.filter_mask, by_hdf5.filter_mask) << field.name << " frame " << frame;
      EXPECT_EQ(filtered.bytes, by_hdf5.bytes) << field.name << " frame " << frame << " at level " << level;
      const Bytes input = frame_of(field, frame);
      expected.insert(expected.end(), input.begin(), input.end());
      // The edge the random frame is there for: deflate grows it, and HDF5 stores it deflated all the
      // same (its filter's buffer is never smaller than zlib's bound), filter mask 0.
      if (level > 0 && frame == kFrames - 1 && field.bytes() > 64) {
        EXPECT_GT(by_hdf5.bytes.size(), input.size()) << field.name;
        EXPECT_EQ(by_hdf5.filter_mask, 0u) << field.name;
      }
      if (level == 0) {
        EXPECT_EQ(by_hdf5.bytes, input) << field.name;
      }
    }
    EXPECT_EQ(decoded(a, field), expected) << field.name;
    EXPECT_EQ(decoded(b, field), expected) << field.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Levels, Hdf5Filters, testing::Values(0, 1, 4, 9),
                         [](const testing::TestParamInfo<int>& info) { return "deflate" + std::to_string(info.param); });

TEST(Hdf5Filters, ShuffleGroupsEachElementsBytesBySignificance) {
  // Two 4-byte elements, then what HDF5's shuffle makes of them: every first byte, every second, ...
  const Bytes elements = {1, 2, 3, 4, 5, 6, 7, 8};
  Bytes chunk;
  shuffle_then_deflate(elements.data(), elements.size(), 4, 1, chunk);
  const Bytes shuffled = {1, 5, 2, 6, 3, 7, 4, 8};
  Bytes deflated(64);
  uLongf size = deflated.size();
  ASSERT_EQ(compress2(deflated.data(), &size, shuffled.data(), shuffled.size(), 1), Z_OK);
  deflated.resize(size);
  EXPECT_EQ(chunk, deflated);
}

TEST(Hdf5Filters, APartElementOrABadLevelIsABug) {
  const Bytes bytes(10);
  Bytes chunk;
  EXPECT_THROW(shuffle_then_deflate(bytes.data(), bytes.size(), 4, 4, chunk), std::logic_error);
  EXPECT_THROW(shuffle_then_deflate(bytes.data(), bytes.size(), 1, 0, chunk), std::logic_error);
  EXPECT_THROW(shuffle_then_deflate(bytes.data(), bytes.size(), 1, 10, chunk), std::logic_error);
}

}  // namespace
}  // namespace bleedsim
