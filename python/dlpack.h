#pragma once
// The DLPack structures that cross the __dlpack__ protocol, as DLPack 1.0 lays them out
// (dmlc/dlpack, include/dlpack/dlpack.h): the legacy DLManagedTensor of a "dltensor" capsule and
// the versioned one of a "dltensor_versioned" capsule. Only what this module exports is named.
// Debian 12 packages no dlpack.h with the versioned structures.
#include <cstdint>

namespace bleedsim::python::dlpack {

constexpr std::int32_t kDLCUDA = 2;
constexpr std::uint8_t kDLUInt = 1;
constexpr std::uint8_t kDLFloat = 2;
constexpr std::uint64_t kReadOnly = 1;  // DLPACK_FLAG_BITMASK_READ_ONLY

struct DLDevice {
  std::int32_t device_type;
  std::int32_t device_id;
};

struct DLDataType {
  std::uint8_t code;
  std::uint8_t bits;
  std::uint16_t lanes;
};

struct DLTensor {
  void* data;
  DLDevice device;
  std::int32_t ndim;
  DLDataType dtype;
  std::int64_t* shape;
  std::int64_t* strides;  // in elements
  std::uint64_t byte_offset;
};

struct DLManagedTensor {
  DLTensor dl_tensor;
  void* manager_ctx;
  void (*deleter)(DLManagedTensor* self);
};

struct DLPackVersion {
  std::uint32_t major;
  std::uint32_t minor;
};

struct DLManagedTensorVersioned {
  DLPackVersion version;
  void* manager_ctx;
  void (*deleter)(DLManagedTensorVersioned* self);
  std::uint64_t flags;
  DLTensor dl_tensor;
};

}  // namespace bleedsim::python::dlpack
