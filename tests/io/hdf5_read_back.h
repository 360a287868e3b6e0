#pragma once
// Reading an HDF5 file back through the C API in tests: handles that close themselves and helpers
// that throw (gtest reports the exception as the test's failure) rather than assert.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/test_paths.h"

namespace bleedsim::test {

// A folder of its own for each test, so tests run in parallel (ctest -j) never meet.
inline std::filesystem::path test_output_folder(const std::string& area) {
  const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path folder = std::filesystem::path(binary_dir()) / "test_output" / area /
                                       (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

template <herr_t (*Close)(hid_t)>
class Owned {
 public:
  explicit Owned(hid_t id) : id_(id) {}
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() {
    if (id_ >= 0) Close(id_);
  }
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
};

// The handles throw rather than assert, so that helpers returning values can use them; gtest
// reports the exception as a failure of the test.
inline hid_t checked(hid_t id, const std::string& what) {
  if (id < 0) throw std::runtime_error("HDF5 read-back failed: " + what);
  return id;
}
inline void checked_status(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5 read-back failed: " + what);
}

struct File : Owned<H5Fclose> {
  explicit File(const std::filesystem::path& path)
      : Owned(
            checked(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path.string())) {}
};
struct Dataset : Owned<H5Dclose> {
  Dataset(hid_t file, const std::string& path)
      : Owned(checked(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "open " + path)) {}
};
using Space = Owned<H5Sclose>;
using Type = Owned<H5Tclose>;
using Plist = Owned<H5Pclose>;
using Attribute = Owned<H5Aclose>;

struct Extent {
  std::vector<hsize_t> dims;
  std::vector<hsize_t> max_dims;
};

inline Extent extent_of(hid_t dataset) {
  Space space(checked(H5Dget_space(dataset), "dataspace"));
  const std::size_t rank = std::size_t(H5Sget_simple_extent_ndims(space));
  Extent extent{std::vector<hsize_t>(rank), std::vector<hsize_t>(rank)};
  checked_status(H5Sget_simple_extent_dims(space, extent.dims.data(), extent.max_dims.data()),
                 "dims");
  return extent;
}

inline std::vector<hsize_t> dims_of(hid_t dataset) { return extent_of(dataset).dims; }

inline std::vector<hsize_t> chunk_of(hid_t dataset) {
  Plist dcpl(checked(H5Dget_create_plist(dataset), "dcpl"));
  std::vector<hsize_t> chunk(8);
  const int rank = H5Pget_chunk(dcpl, int(chunk.size()), chunk.data());
  checked_status(rank, "chunk");
  chunk.resize(std::size_t(rank));
  return chunk;
}

inline std::vector<H5Z_filter_t> filters_of(hid_t dataset) {
  Plist dcpl(checked(H5Dget_create_plist(dataset), "dcpl"));
  std::vector<H5Z_filter_t> filters;
  for (int i = 0; i < H5Pget_nfilters(dcpl); ++i) {
    unsigned flags = 0;
    size_t values = 0;
    filters.push_back(
        H5Pget_filter2(dcpl, unsigned(i), &flags, &values, nullptr, 0, nullptr, nullptr));
  }
  return filters;
}

struct Text {
  std::string value;
  bool variable_length = false;
  H5T_cset_t cset = H5T_CSET_ERROR;
  H5T_str_t padding = H5T_STR_ERROR;
};

inline Text text_attribute(hid_t object, const char* name) {
  Attribute attribute(
      checked(H5Aopen(object, name, H5P_DEFAULT), std::string("attribute ") + name));
  Type type(checked(H5Aget_type(attribute), "attribute type"));
  if (H5Tget_class(type) != H5T_STRING)
    throw std::runtime_error(std::string("attribute ") + name + " is not a string");
  Text text;
  text.variable_length = H5Tis_variable_str(type) > 0;
  text.cset = H5Tget_cset(type);
  text.padding = H5Tget_strpad(type);
  if (text.variable_length) {
    char* value = nullptr;
    checked_status(H5Aread(attribute, type, &value), "read string");
    text.value = value ? value : "";
    H5free_memory(value);
  } else {
    std::vector<char> value(H5Tget_size(type) + 1, '\0');
    checked_status(H5Aread(attribute, type, value.data()), "read string");
    text.value = value.data();
  }
  return text;
}

template <class T>
T scalar_attribute(hid_t object, const char* name, hid_t memory_type) {
  Attribute attribute(
      checked(H5Aopen(object, name, H5P_DEFAULT), std::string("attribute ") + name));
  T value{};
  checked_status(H5Aread(attribute, memory_type, &value), std::string("read ") + name);
  return value;
}

// All of one dataset as stored, frames one after another.
template <class T>
std::vector<T> read_all(hid_t dataset, hid_t memory_type) {
  std::size_t count = 1;
  for (const hsize_t extent : dims_of(dataset)) count *= std::size_t(extent);
  std::vector<T> values(count);
  checked_status(H5Dread(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
                 "read data");
  return values;
}

}  // namespace bleedsim::test
