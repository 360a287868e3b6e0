#include "core/runtime/backend.h"

#include <stdexcept>

namespace bleedsim {

const char* to_string(BackendKind kind) { return kind == BackendKind::cuda ? "cuda" : "cpu"; }

Buffer Backend::allocate(std::size_t bytes) {
  if (bytes == 0) return Buffer();
  void* data = allocate_raw(bytes);
  *bytes_in_use_ += bytes;
  std::weak_ptr<std::size_t> in_use = bytes_in_use_;
  return Buffer(data, bytes, [this, bytes, in_use](void* p) {
    if (auto counter = in_use.lock()) {
      *counter -= bytes;
      release_raw(p);
    }
  });
}

std::uint64_t Backend::launches(const std::string& stage) const {
  const auto it = launches_.find(stage);
  return it == launches_.end() ? 0 : it->second;
}

SelectedBackend select_backend(const BackendChoice& choice) {
  using Want = BackendChoice::Want;
  if (choice.want == Want::cpu) return {make_cpu_backend(choice.cpu_threads), "asked for cpu"};
  std::string why_not;
  const bool cuda = cuda_device_available(&why_not);
  if (choice.want == Want::cuda) {
    if (!cuda) throw std::runtime_error("the cuda backend is not available: " + why_not);
    return {make_cuda_backend(choice.cuda_device), "asked for cuda"};
  }
  if (cuda) return {make_cuda_backend(choice.cuda_device), "auto: CUDA device found"};
  return {make_cpu_backend(choice.cpu_threads), "auto: " + why_not};
}

}  // namespace bleedsim
