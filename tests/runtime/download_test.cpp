// A Download carries each field as the work queued before it left it, though the work queued after
// it changes the field at once (the next frame): on CUDA the copy runs while that work does, into
// the backend's host memory (page-locked there).
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/runtime/backend.h"

namespace bleedsim {
namespace {

class Downloads : public testing::TestWithParam<BackendChoice::Want> {};

// Frame f's two fields hold f's own values; a run's two downloads alternate, each finished a frame
// later, after the next frame has overwritten the fields. The second field grows after two frames.
TEST_P(Downloads, CarryTheFieldsAsTheWorkBeforeThemLeftThem) {
  std::string why;
  if (GetParam() == BackendChoice::Want::cuda && !cuda_device_available(&why)) GTEST_SKIP() << "no CUDA device: " << why;
  const std::unique_ptr<Backend> backend = select_backend(BackendChoice{GetParam(), 2}).backend;
  const std::size_t small = 1u << 16, large = 1u << 20;  // values of a field, 4 bytes each
  const Buffer a = backend->allocate(large * 4), b = backend->allocate(large * 4);
  const std::unique_ptr<Download> downloads[2] = {backend->make_download(), backend->make_download()};
  using Values = std::vector<std::uint32_t, HostAllocator<std::uint32_t>>;
  const HostAllocator<std::uint32_t> host(&backend->host_memory());
  Values host_a[2] = {Values(host), Values(host)}, host_b[2] = {Values(host), Values(host)};
  const auto values = [](int frame, std::size_t n, std::uint32_t field) {
    std::vector<std::uint32_t> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = std::uint32_t(frame) * 2654435761u + std::uint32_t(i) * 40503u + field;
    return v;
  };
  const auto b_size = [&](int frame) { return frame < 2 ? small : large; };
  const int frames = 5;
  for (int f = 0; f <= frames; ++f) {
    if (f < frames) {
      const std::vector<std::uint32_t> va = values(f, large, 1), vb = values(f, b_size(f), 2);
      backend->upload(a.data(), va.data(), va.size() * 4);
      backend->upload(b.data(), vb.data(), vb.size() * 4);
      host_a[f % 2].assign(large, 0u);
      host_b[f % 2].assign(b_size(f), 0u);
      downloads[f % 2]->add(host_a[f % 2].data(), a.data(), large * 4);
      downloads[f % 2]->add(host_b[f % 2].data(), b.data(), b_size(f) * 4);
    }
    if (f == 0) continue;
    const int done = f - 1;  // its fields were overwritten by frame f's upload (or the run ended)
    downloads[done % 2]->finish();
    const std::vector<std::uint32_t> got_a(host_a[done % 2].begin(), host_a[done % 2].end()),
        got_b(host_b[done % 2].begin(), host_b[done % 2].end());
    EXPECT_EQ(got_a, values(done, large, 1)) << "frame " << done;
    EXPECT_EQ(got_b, values(done, b_size(done), 2)) << "frame " << done;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Downloads, testing::Values(BackendChoice::Want::cpu, BackendChoice::Want::cuda),
                         [](const testing::TestParamInfo<BackendChoice::Want>& info) {
                           return info.param == BackendChoice::Want::cpu ? "cpu" : "cuda";
                         });

}  // namespace
}  // namespace bleedsim
