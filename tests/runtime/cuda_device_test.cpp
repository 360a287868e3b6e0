// The CUDA backend runs on the device BackendChoice::cuda_device names (each MPI rank of a study
// on its own GPU: core/scaleout/ranks.h), and refuses one that is not there.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "core/runtime/backend.h"

#if BLEEDSIM_HAVE_CUDA
#include <cuda_runtime.h>
#endif

namespace bleedsim {
namespace {

TEST(CudaDevice, AnIndexThatIsNoDeviceIsRefusedWithTheDevicesThereAre) {
  const int count = cuda_device_count();
  for (const int device : {-1, count}) {
    try {
      select_backend(BackendChoice{BackendChoice::Want::cuda, 0, device});
      ADD_FAILURE() << "device " << device << " accepted";
    } catch (const std::runtime_error& e) {
      const std::string expected = count > 0 ? "CUDA device " + std::to_string(device) + " was asked for; this process sees "
                                             : "the cuda backend is not available";
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

TEST(CudaDevice, EachDevicesBackendAllocatesOnThatDevice) {
  const int count = cuda_device_count();
  if (count == 0) {
    std::string why;
    cuda_device_available(&why);
    GTEST_SKIP() << "no CUDA device to check: " << why;
  }
#if BLEEDSIM_HAVE_CUDA
  // One device shows only that the index is taken; the GPU machines with several show the rest.
  for (int device = count - 1; device >= 0; --device) {
    const std::unique_ptr<Backend> backend = make_cuda_backend(device);
    EXPECT_NE(backend->device_name().find("(device " + std::to_string(device) + ":"), std::string::npos)
        << backend->device_name();
    const Buffer buffer = backend->allocate(256);
    cudaPointerAttributes attributes{};
    ASSERT_EQ(cudaPointerGetAttributes(&attributes, buffer.data()), cudaSuccess);
    EXPECT_EQ(attributes.device, device);
    EXPECT_EQ(attributes.type, cudaMemoryTypeDevice);
  }
#endif
}

}  // namespace
}  // namespace bleedsim
