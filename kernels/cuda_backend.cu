// The CUDA backend: device memory; Backend::run calls the CUDA twins (the launches in this folder).
#include <cuda_runtime.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/physics/particles.h"
#include "core/runtime/backend.h"
#include "kernels/cuda_check.h"

namespace bleedsim {

void cuda_check(cudaError_t status, const char* call, const char* file, int line) {
  if (status == cudaSuccess) return;
  throw std::runtime_error(std::string(call) + " failed at " + file + ":" + std::to_string(line) +
                           ": " + cudaGetErrorName(status) + " (" + cudaGetErrorString(status) + ")");
}

void check_launch(const char* kernel) {
  const cudaError_t status = cudaGetLastError();
  if (status != cudaSuccess)
    throw std::runtime_error(std::string("launch of ") + kernel + " failed: " +
                             cudaGetErrorName(status) + " (" + cudaGetErrorString(status) + ")");
}

namespace {

class CudaEvent {
 public:
  CudaEvent() { BLEEDSIM_CUDA_CHECK(cudaEventCreate(&event_)); }
  ~CudaEvent() { cudaEventDestroy(event_); }
  CudaEvent(const CudaEvent&) = delete;
  CudaEvent& operator=(const CudaEvent&) = delete;
  cudaEvent_t get() const { return event_; }

 private:
  cudaEvent_t event_{};
};

// Page-locked host memory: the GPU's copy engines write it directly, at the link's full rate, while
// the GPU computes.
class PinnedMemory final : public HostMemory {
 public:
  void* allocate(std::size_t bytes) override {
    void* data = nullptr;
    BLEEDSIM_CUDA_CHECK(cudaMallocHost(&data, bytes));
    return data;
  }
  void release(void* data) noexcept override { cudaFreeHost(data); }
};

// A frame's fields on their way to the host while the next frame computes. Each is copied aside on
// the device in the work's order (on the default stream: a device-to-device copy of microseconds),
// then sent from that copy to its destination on a stream that waits for the copy aside alone, so
// the next frame's kernels, queued behind the copy aside, run meanwhile. The copies aside stay from
// frame to frame.
class CudaDownload final : public Download {
 public:
  explicit CudaDownload(Backend& backend) : backend_(backend) {
    BLEEDSIM_CUDA_CHECK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking));
  }
  ~CudaDownload() override {
    cudaStreamSynchronize(stream_);
    cudaStreamDestroy(stream_);
  }
  CudaDownload(const CudaDownload&) = delete;
  CudaDownload& operator=(const CudaDownload&) = delete;

  void add(void* dst, const void* src, std::size_t bytes) override {
    if (added_ == aside_.size()) aside_.emplace_back();
    Buffer& aside = aside_[added_++];
    // Grown only between rounds: finish() has waited for every transfer out of the old one.
    if (aside.bytes() < bytes) aside = backend_.allocate(bytes);
    BLEEDSIM_CUDA_CHECK(cudaMemcpyAsync(aside.data(), src, bytes, cudaMemcpyDeviceToDevice, cudaStreamLegacy));
    BLEEDSIM_CUDA_CHECK(cudaEventRecord(taken_.get(), cudaStreamLegacy));
    BLEEDSIM_CUDA_CHECK(cudaStreamWaitEvent(stream_, taken_.get(), 0));
    BLEEDSIM_CUDA_CHECK(cudaMemcpyAsync(dst, aside.data(), bytes, cudaMemcpyDeviceToHost, stream_));
  }
  void finish() override {
    BLEEDSIM_CUDA_CHECK(cudaStreamSynchronize(stream_));
    added_ = 0;
  }

 private:
  Backend& backend_;
  cudaStream_t stream_{};
  CudaEvent taken_;
  std::vector<Buffer> aside_;  // on the device, one a field
  std::size_t added_ = 0;      // copies in this round
};

class CudaBackend final : public Backend {
 public:
  explicit CudaBackend(int device) : device_(device) {
    const int count = cuda_device_count();
    if (device < 0 || device >= count) {
      const std::string seen = count == 0   ? "none"
                               : count == 1 ? "1 device (0)"
                                            : std::to_string(count) + " devices (0 to " + std::to_string(count - 1) + ")";
      throw std::runtime_error("CUDA device " + std::to_string(device) + " was asked for; this process sees " + seen);
    }
    // Allocations, copies and launches go to the calling thread's current device.
    BLEEDSIM_CUDA_CHECK(cudaSetDevice(device_));
    BLEEDSIM_CUDA_CHECK(cudaGetDeviceProperties(&properties_, device_));
  }

  BackendKind kind() const override { return BackendKind::cuda; }
  std::string device_name() const override {
    char text[320];
    std::snprintf(text, sizeof text, "%s (device %d: sm_%d%d, %.0f GiB)", properties_.name, device_,
                  properties_.major, properties_.minor, properties_.totalGlobalMem / 1073741824.0);
    return text;
  }
  void upload(void* dst, const void* src, std::size_t bytes) override {
    BLEEDSIM_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyHostToDevice));
  }
  void download(void* dst, const void* src, std::size_t bytes) override {
    BLEEDSIM_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToHost));
  }
  void synchronize() override { BLEEDSIM_CUDA_CHECK(cudaDeviceSynchronize()); }
  HostMemory& host_memory() override { return host_memory_; }
  std::unique_ptr<Download> make_download() override { return std::make_unique<CudaDownload>(*this); }
  std::size_t memory_available() const override {
    std::size_t free_bytes = 0, total_bytes = 0;
    BLEEDSIM_CUDA_CHECK(cudaMemGetInfo(&free_bytes, &total_bytes));
    return free_bytes;
  }
  std::size_t particle_sort_scratch_bytes(int capacity, std::uint32_t cells) const override {
    return particle_sort_scratch_cuda(capacity, cells);
  }
  double time_ms(const std::function<void()>& work) override {
    CudaEvent start, stop;
    BLEEDSIM_CUDA_CHECK(cudaEventRecord(start.get()));
    work();
    BLEEDSIM_CUDA_CHECK(cudaEventRecord(stop.get()));
    BLEEDSIM_CUDA_CHECK(cudaEventSynchronize(stop.get()));
    float ms = 0.0f;
    BLEEDSIM_CUDA_CHECK(cudaEventElapsedTime(&ms, start.get(), stop.get()));
    return ms;
  }

 protected:
  void* allocate_raw(std::size_t bytes) override {
    void* data = nullptr;
    BLEEDSIM_CUDA_CHECK(cudaMalloc(&data, bytes));
    return data;
  }
  void release_raw(void* data) override { cudaFree(data); }

 private:
  int device_ = 0;
  cudaDeviceProp properties_{};
  PinnedMemory host_memory_;
};

}  // namespace

std::unique_ptr<Backend> make_cuda_backend(int device) { return std::make_unique<CudaBackend>(device); }

bool cuda_device_available(std::string* why_not) {
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    // The static runtime reports a machine with no NVIDIA driver at all as an insufficient one.
    const char* meaning = status == cudaErrorInsufficientDriver
                              ? "no NVIDIA driver, or one older than this build's CUDA runtime"
                              : cudaGetErrorString(status);
    *why_not = std::string("no usable CUDA device (") + cudaGetErrorName(status) + ": " + meaning + ")";
    cudaGetLastError();  // clear the error so later calls start clean
    return false;
  }
  if (count == 0) {
    *why_not = "no CUDA device";
    return false;
  }
  return true;
}

int cuda_device_count() {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();  // clear the error so later calls start clean
    return 0;
  }
  return count;
}

}  // namespace bleedsim
