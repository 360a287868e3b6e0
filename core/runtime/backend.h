#pragma once
// A backend is where the physics runs: the CPU reference (always) or CUDA (when built and a device
// is present). It owns memory and runs stage twins; it holds no formulas, which live in core/, and
// knows no effect: a twin pair is found by its argument types.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/runtime/buffer.h"
#include "core/runtime/download.h"

// Backend::run below must see whether the CUDA twins exist: bleedsim::core's CMake target says.
#ifndef BLEEDSIM_HAVE_CUDA
#error "BLEEDSIM_HAVE_CUDA is not defined: link the bleedsim::core target, which defines it"
#endif

namespace bleedsim {

enum class BackendKind { cpu, cuda };
const char* to_string(BackendKind kind);

class Backend {
 public:
  virtual ~Backend() = default;
  virtual BackendKind kind() const = 0;
  // What it runs on, for people: "cpu (8 threads)", "NVIDIA H100 80GB HBM3 (sm_90)".
  virtual std::string device_name() const = 0;

  Buffer allocate(std::size_t bytes);
  virtual void upload(void* dst, const void* src, std::size_t bytes) = 0;
  virtual void download(void* dst, const void* src, std::size_t bytes) = 0;
  virtual void synchronize() = 0;
  // Host memory for fields copied out frame after frame, and a Download to copy them: on the CPU
  // ordinary memory and each copy made as it is added; on CUDA page-locked memory, each field taken
  // aside on the device and sent from there on a stream of its own while the next frame computes.
  virtual HostMemory& host_memory() = 0;
  virtual std::unique_ptr<Download> make_download() = 0;
  // Memory it can still allocate, in bytes.
  virtual std::size_t memory_available() const = 0;
  // Milliseconds `work` takes as the backend sees it: the wall clock on the CPU, CUDA events
  // around the launches on the device. For benchmarks.
  virtual double time_ms(const std::function<void()>& work) = 0;

  // Runs one piece of a stage's work, counted under `stage` so a pipeline can prove what it ran:
  // cpu_twin(a..., threads) on the CPU, cuda_twin(a...) on CUDA, the twin pair that the
  // arguments' physics header declares (core/physics/; per-pixel work: pixel_kernels.h).
  template <class... A>
  void run(const std::string& stage, const A&... a) {
    ++launches_[stage];
    dispatch(a...);
  }
  // The same for work that several stages share in one pass (pair_pixels), counted under each.
  template <class... A>
  void run_shared(const std::vector<std::string>& stages, const A&... a) {
    for (const std::string& stage : stages) ++launches_[stage];
    dispatch(a...);
  }
  // Temporary storage the particle bin needs here (none on the CPU; on the GPU its counts and places).
  virtual std::size_t particle_sort_scratch_bytes(int capacity, std::uint32_t cells) const = 0;

  std::uint64_t launches(const std::string& stage) const;
  std::size_t bytes_in_use() const { return *bytes_in_use_; }

 protected:
  // `cpu_threads`: the threads the CPU twins run on (the CPU backend's; unused on CUDA).
  explicit Backend(int cpu_threads = 1) : cpu_threads_(cpu_threads) {}
  virtual void* allocate_raw(std::size_t bytes) = 0;
  virtual void release_raw(void* data) = 0;

  const int cpu_threads_;

 private:
  template <class... A>
  void dispatch(const A&... a) {
#if BLEEDSIM_HAVE_CUDA
    if (kind() == BackendKind::cuda) {
      cuda_twin(a...);
      return;
    }
#endif
    cpu_twin(a..., cpu_threads_);
  }

  std::map<std::string, std::uint64_t> launches_;
  // Shared with the buffers' release, so a buffer that outlives accounting cannot write freed memory.
  std::shared_ptr<std::size_t> bytes_in_use_ = std::make_shared<std::size_t>(0);
};

// Which backend a run asks for; "auto" takes CUDA when a device is present.
struct BackendChoice {
  enum class Want { automatic, cpu, cuda } want = Want::automatic;
  int cpu_threads = 0;  // 0: one per hardware thread
  int cuda_device = 0;  // which device the cuda backend runs on (each MPI rank its own: Ranks::cuda_device)
};

struct SelectedBackend {
  std::unique_ptr<Backend> backend;
  std::string why;  // e.g. "auto: no CUDA device (cudaErrorNoDevice)", shown to the user
};

// Throws std::runtime_error when "cuda" is asked for and cannot be had, and when the CUDA backend
// is chosen (asked for, or "auto" with a device present) and its device index is not one there is.
SelectedBackend select_backend(const BackendChoice& choice);

// Implemented by reference_cpu/ and kernels/ (kernels/no_cuda.cpp in a build without nvcc).
std::unique_ptr<Backend> make_cpu_backend(int threads);
// On CUDA device `device` (0 to cuda_device_count() - 1; else std::runtime_error naming the count),
// which it makes current on the calling thread: drive it from that thread, as CUDA's current
// device is per thread.
std::unique_ptr<Backend> make_cuda_backend(int device = 0);
// True when this build has the CUDA backend and a usable device; otherwise says why not.
bool cuda_device_available(std::string* why_not);
// The CUDA devices this process sees (after CUDA_VISIBLE_DEVICES); 0 without the backend or a device.
int cuda_device_count();

}  // namespace bleedsim
