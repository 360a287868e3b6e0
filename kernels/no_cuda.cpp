// A build without nvcc has no CUDA backend; it says so instead of failing to link.
#include <stdexcept>

#include "core/runtime/backend.h"

namespace bleedsim {
namespace {
const char* const kNoCuda = "this build has no CUDA backend (nvcc was not found when it was configured)";
}

std::unique_ptr<Backend> make_cuda_backend(int) { throw std::runtime_error(kNoCuda); }

bool cuda_device_available(std::string* why_not) {
  *why_not = kNoCuda;
  return false;
}

int cuda_device_count() { return 0; }

}  // namespace bleedsim
