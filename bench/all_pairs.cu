// The all-pairs baseline over device memory (bench/all_pairs.h): one thread per particle; the block
// loads a tile of kTile particles into shared memory, every thread tests its particle against the
// whole tile, then the next tile. Slots are visited in order, as on the CPU.
#include "bench/all_pairs.h"
#include "kernels/cuda_check.h"

namespace bleedsim {
namespace {

constexpr int kTile = 256;

__global__ void all_pairs_kernel(ParticleArrays p, ParticleModel m) {
  __shared__ float4 tile[kTile];  // x, y, vx, vy
  __shared__ std::uint32_t tile_age[kTile];
  const int i = blockIdx.x * kTile + threadIdx.x;
  const std::uint32_t age = i < p.capacity ? p.age[i] : kNeverUsed;
  const bool mine = is_alive(m, age);
  float px = 0.0f, py = 0.0f, vx = 0.0f, vy = 0.0f;
  if (mine) {
    px = p.position[2 * i];
    py = p.position[2 * i + 1];
    vx = p.velocity[2 * i];
    vy = p.velocity[2 * i + 1];
  }
  PairSums sums;
  for (int base = 0; base < p.capacity; base += kTile) {
    const int j = base + int(threadIdx.x);
    if (j < p.capacity) {
      tile[threadIdx.x] = make_float4(p.position[2 * j], p.position[2 * j + 1], p.velocity[2 * j],
                                      p.velocity[2 * j + 1]);
      tile_age[threadIdx.x] = p.age[j];
    }
    __syncthreads();
    const int count = min(kTile, p.capacity - base);
    if (mine)
      for (int k = 0; k < count; ++k) {
        const float4 q = tile[k];
        all_pairs_accumulate(m, px, py, vx, vy, age, std::uint32_t(i), q.x, q.y, q.z, q.w, tile_age[k],
                             std::uint32_t(base + k), &sums);
      }
    __syncthreads();
  }
  if (mine) {
    finish_pair_sums(p, m, std::uint32_t(i), sums);
  }
}

}  // namespace

void all_pairs_collide_cuda(const ParticleArrays& p, const ParticleModel& m) {
  all_pairs_kernel<<<(p.capacity + kTile - 1) / kTile, kTile>>>(p, m);
  check_launch("all_pairs_kernel");
}

void copy_device_to_device_cuda(void* dst, const void* src, std::size_t bytes) {
  BLEEDSIM_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToDevice));
}

}  // namespace bleedsim
