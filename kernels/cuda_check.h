#pragma once
#include <cuda_runtime.h>

namespace bleedsim {

// Throws std::runtime_error naming the call and the CUDA error when `status` is not success.
void cuda_check(cudaError_t status, const char* call, const char* file, int line);
// After a launch: a bad configuration shows here, a fault in the kernel at the next sync.
void check_launch(const char* kernel);

}  // namespace bleedsim

#define BLEEDSIM_CUDA_CHECK(call) ::bleedsim::cuda_check((call), #call, __FILE__, __LINE__)
