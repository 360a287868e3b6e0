// The CPU reference backend: host memory; Backend::run calls the CPU twins (the loops in this folder).
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <string>
#include <thread>

#include "core/runtime/backend.h"
#include "core/runtime/memory.h"

namespace bleedsim {
namespace {

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

class OrdinaryMemory final : public HostMemory {
 public:
  void* allocate(std::size_t bytes) override { return ::operator new(bytes); }
  void release(void* data) noexcept override { ::operator delete(data); }
};

// Host memory to host memory: nothing runs on while the run copies, so each copy is made at once.
class CopyAtOnce final : public Download {
 public:
  void add(void* dst, const void* src, std::size_t bytes) override { std::memcpy(dst, src, bytes); }
  void finish() override {}
};

class CpuBackend final : public Backend {
 public:
  explicit CpuBackend(int threads)
      : Backend(threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()))) {}

  BackendKind kind() const override { return BackendKind::cpu; }
  std::string device_name() const override {
    return cpu_model() + ", " + std::to_string(cpu_threads_) + (cpu_threads_ == 1 ? " thread" : " threads");
  }
  void upload(void* dst, const void* src, std::size_t bytes) override { std::memcpy(dst, src, bytes); }
  void download(void* dst, const void* src, std::size_t bytes) override { std::memcpy(dst, src, bytes); }
  void synchronize() override {}
  HostMemory& host_memory() override { return host_memory_; }
  std::unique_ptr<Download> make_download() override { return std::make_unique<CopyAtOnce>(); }
  std::size_t memory_available() const override { return available_host_memory(); }
  std::size_t particle_sort_scratch_bytes(int, std::uint32_t) const override { return 0; }
  double time_ms(const std::function<void()>& work) override {
    const auto start = std::chrono::steady_clock::now();
    work();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

 protected:
  void* allocate_raw(std::size_t bytes) override {
    constexpr std::size_t kAlign = 64;
    void* data = std::aligned_alloc(kAlign, (bytes + kAlign - 1) / kAlign * kAlign);
    if (!data) throw std::bad_alloc();
    return data;
  }
  void release_raw(void* data) override { std::free(data); }

 private:
  OrdinaryMemory host_memory_;
};

}  // namespace

std::unique_ptr<Backend> make_cpu_backend(int threads) { return std::make_unique<CpuBackend>(threads); }

}  // namespace bleedsim
