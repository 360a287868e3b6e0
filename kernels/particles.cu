// The CUDA twin of the particle step: launches of core/physics/particles.h. The sort is CUB's radix sort
// on the cell key with the slot as value; it is stable, so it orders (cell, slot) exactly as the
// CPU reference's counting sort does.
#include <cub/device/device_radix_sort.cuh>

#include <cstddef>

#include "core/physics/particles.h"
#include "kernels/cuda_check.h"

namespace bleedsim {
namespace {

constexpr int kThreads = 256;

int blocks_for(int count) { return (count + kThreads - 1) / kThreads; }

__global__ void emit_kernel(ParticleArgs a) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < a.new_count) emit_particle(a, t);
}

__global__ void cell_key_kernel(ParticleArrays p, ParticleModel m) {
  const int slot = blockIdx.x * blockDim.x + threadIdx.x;
  if (slot < p.capacity) p.cell_key[slot] = cell_key_of(p, m, slot);
}

// The live particles sort first (empty slots carry the largest key): only they need ranges,
// sorted copies and contacts.
__global__ void cell_range_kernel(ParticleArrays p, ParticleModel m, int live) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= live) return;
  mark_cell_range(p, m, i);
  gather_sorted(p, i);
}

__global__ void collide_kernel(ParticleArrays p, ParticleModel m, int live) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < live) collide_particle(p, m, i);
}

__global__ void integrate_kernel(ParticleArgs a) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < a.live_count) integrate_particle(a.arrays, a.model, live_slot(a, t));
}

void sort_by_cell(const ParticleArrays& p, const ParticleModel& m) {
  std::size_t bytes = p.sort_scratch_bytes;
  BLEEDSIM_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(p.sort_scratch, bytes, p.cell_key, p.sorted_key,
                                                      p.slot_index, p.sorted_slot, p.capacity, 0, m.key_bits));
}

void bin(const ParticleArgs& a) {
  const ParticleArrays& p = a.arrays;
  const std::size_t cells = cell_count(a.model);
  cell_key_kernel<<<blocks_for(p.capacity), kThreads>>>(p, a.model);
  check_launch("cell_key_kernel");
  sort_by_cell(p, a.model);
  // Empty cells keep start = end = 0: an empty range, as on the CPU.
  BLEEDSIM_CUDA_CHECK(cudaMemsetAsync(p.cell_start, 0, cells * sizeof(std::uint32_t)));
  BLEEDSIM_CUDA_CHECK(cudaMemsetAsync(p.cell_end, 0, cells * sizeof(std::uint32_t)));
  if (a.live_count == 0) return;
  cell_range_kernel<<<blocks_for(a.live_count), kThreads>>>(p, a.model, a.live_count);
  check_launch("cell_range_kernel");
}

}  // namespace

std::size_t particle_sort_scratch_cuda(int capacity, int key_bits) {
  std::size_t bytes = 0;
  BLEEDSIM_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, static_cast<std::uint32_t*>(nullptr),
                                                      static_cast<std::uint32_t*>(nullptr),
                                                      static_cast<std::uint32_t*>(nullptr),
                                                      static_cast<std::uint32_t*>(nullptr), capacity, 0,
                                                      key_bits));
  return bytes;
}

void cuda_twin(ParticlePhase phase, const ParticleArgs& a) {
  const int n = a.live_count;
  switch (phase) {
    case ParticlePhase::emit:
      if (a.new_count == 0) return;
      emit_kernel<<<blocks_for(a.new_count), kThreads>>>(a);
      check_launch("emit_kernel");
      break;
    case ParticlePhase::bin:
      bin(a);
      break;
    case ParticlePhase::collide:
      if (n == 0) return;
      collide_kernel<<<blocks_for(n), kThreads>>>(a.arrays, a.model, n);
      check_launch("collide_kernel");
      break;
    case ParticlePhase::integrate:
      if (n == 0) return;
      integrate_kernel<<<blocks_for(n), kThreads>>>(a);
      check_launch("integrate_kernel");
      break;
  }
}

}  // namespace bleedsim
