#pragma once
// Fields copied out of a backend while it computes on: a run hands each frame's fields to its
// output while the next frame computes, into host memory the backend copies into fastest.
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace bleedsim {

// Host memory a backend copies into fastest: page-locked on CUDA, where a copy into it runs on the
// GPU's copy engines while the GPU computes; ordinary on the CPU.
class HostMemory {
 public:
  virtual ~HostMemory() = default;
  virtual void* allocate(std::size_t bytes) = 0;
  virtual void release(void* data) noexcept = 0;
};

// A standard allocator over a HostMemory (ordinary memory where it has none): a run's buffers for
// the fields it copies out, kept from frame to frame.
template <class T>
struct HostAllocator {
  using value_type = T;
  HostMemory* memory = nullptr;

  HostAllocator() = default;
  explicit HostAllocator(HostMemory* m) : memory(m) {}
  template <class U>
  HostAllocator(const HostAllocator<U>& other) : memory(other.memory) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    return static_cast<T*>(memory ? memory->allocate(bytes) : ::operator new(bytes));
  }
  void deallocate(T* data, std::size_t) noexcept {
    if (memory)
      memory->release(data);
    else
      ::operator delete(data);
  }
  template <class U>
  bool operator==(const HostAllocator<U>& other) const { return memory == other.memory; }
  template <class U>
  bool operator!=(const HostAllocator<U>& other) const { return memory != other.memory; }
};

using HostBytes = std::vector<std::uint8_t, HostAllocator<std::uint8_t>>;

// Fields on their way from a backend into host memory while the backend computes on.
class Download {
 public:
  virtual ~Download() = default;
  // Copies `bytes` at `src` (backend memory, as the work queued before this call leaves it) to host
  // memory `dst` (the backend's HostMemory, for the copy to overlap the work), whole once finish()
  // returns: work queued after this call may change src at once, and dst must stay put until then.
  virtual void add(void* dst, const void* src, std::size_t bytes) = 0;
  // Waits for the copies added since the last finish().
  virtual void finish() = 0;
};

}  // namespace bleedsim
