// The CUDA twin of the suction: launches of core/physics/instrument.h. Nearest first is a radix
// select in one block: the quota-th smallest candidate key found eight bits at a time from a
// histogram of the candidates that share the digits found so far (integer counts, so the same in
// any order); the keys are unique, so those at or below it are exactly the quota nearest, the set
// the CPU's partial sort selects.
#include <cstdint>

#include "core/physics/instrument.h"
#include "kernels/cuda_check.h"

namespace bleedsim {
namespace {

constexpr int kThreads = 256;
constexpr int kSelectThreads = 1024;

int blocks_for(int count) { return (count + kThreads - 1) / kThreads; }

// Every live particle within reach adds its key to the candidates, in whatever order.
__global__ void candidates_kernel(InstrumentArgs a) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= a.live_count) return;
  const std::uint64_t key = aspiration_key(a, live_slot(a, t));
  if (key == kNoCandidate) return;
  a.candidates[atomicAdd(a.candidate_count, 1u)] = key;
}

__global__ void select_nearest_kernel(InstrumentArgs a) {
  __shared__ unsigned int histogram[256];
  __shared__ unsigned long long found;  // the digits of the quota-th smallest key found so far
  __shared__ unsigned int rank;         // its rank among the keys that share those digits
  const std::uint32_t n = *a.candidate_count, take = n < a.quota ? n : a.quota;
  std::uint64_t last = kNoCandidate;  // the largest key taken
  if (take < n) {
    if (threadIdx.x == 0) {
      found = 0;
      rank = take;
    }
    for (int shift = 56; shift >= 0; shift -= 8) {
      for (int d = threadIdx.x; d < 256; d += blockDim.x) histogram[d] = 0;
      __syncthreads();
      const std::uint64_t higher = shift == 56 ? 0 : ~std::uint64_t(0) << (shift + 8);
      for (std::uint32_t i = threadIdx.x; i < n; i += blockDim.x) {
        const std::uint64_t key = a.candidates[i];
        if ((key & higher) == found) atomicAdd(&histogram[(key >> shift) & 255u], 1u);
      }
      __syncthreads();
      if (threadIdx.x == 0) {
        unsigned int below = 0, digit = 0;
        while (below + histogram[digit] < rank) below += histogram[digit++];
        found |= (unsigned long long)digit << shift;
        rank -= below;
      }
      __syncthreads();
    }
    last = found;
  }
  for (std::uint32_t i = threadIdx.x; i < n; i += blockDim.x)
    if (a.candidates[i] <= last) aspirate(a.arrays, a.candidates[i]);
  // Every thread has read the count: the next step starts from none.
  __syncthreads();
  if (threadIdx.x == 0) {
    a.arrays.fates->aspirated += take;
    *a.candidate_count = 0;
  }
}

}  // namespace

void cuda_twin(const InstrumentArgs& a) {
  if (a.live_count == 0) return;
  candidates_kernel<<<blocks_for(a.live_count), kThreads>>>(a);
  check_launch("candidates_kernel");
  select_nearest_kernel<<<1, kSelectThreads>>>(a);
  check_launch("select_nearest_kernel");
}

}  // namespace bleedsim
