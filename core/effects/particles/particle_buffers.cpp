#include "core/effects/particles/particle_buffers.h"

#include <algorithm>
#include <vector>

namespace bleedsim {
namespace {

// Offsets of the scratch arrays, one after another, each aligned for vector loads.
struct ScratchLayout {
  std::size_t acceleration, shift, grip, neighbourhood, cell_key, sorted_key, sorted_slot, sorted_position,
      sorted_velocity, sorted_birth, sorted_depth, line_weight, cell_start, fates, sort_scratch, total;

  ScratchLayout(std::size_t cells, std::size_t line_nodes, int capacity, std::size_t sort_scratch_bytes) {
    const std::size_t n = std::size_t(capacity);
    std::size_t at = 0;
    const auto take = [&](std::size_t bytes) {
      const std::size_t here = at;
      at += (bytes + 255) / 256 * 256;
      return here;
    };
    acceleration = take(2 * n * sizeof(float));
    shift = take(2 * n * sizeof(float));
    grip = take(n * sizeof(float));
    neighbourhood = take(n * sizeof(std::uint32_t));
    cell_key = take(n * sizeof(std::uint32_t));
    sorted_key = take(n * sizeof(std::uint32_t));
    sorted_slot = take(n * sizeof(std::uint32_t));
    sorted_position = take(2 * n * sizeof(float));
    sorted_velocity = take(2 * n * sizeof(float));
    sorted_birth = take(n * sizeof(std::uint32_t));
    sorted_depth = take(n * sizeof(float));
    line_weight = take(line_nodes * sizeof(float));
    cell_start = take((cells + 1) * sizeof(std::uint32_t));
    fates = take(sizeof(AspiratedFates));
    sort_scratch = take(sort_scratch_bytes);
    total = at;
  }
};

template <class T>
T* at_offset(void* base, std::size_t offset) {
  return reinterpret_cast<T*>(static_cast<char*>(base) + offset);
}

}  // namespace

std::size_t particle_scratch_bytes(std::size_t cells, std::size_t line_nodes, int capacity,
                                   std::size_t sort_scratch_bytes) {
  return ScratchLayout(cells, line_nodes, capacity, sort_scratch_bytes).total;
}

void point_particle_scratch(ParticleArrays& a, std::size_t cells, std::size_t line_nodes, void* base,
                            std::size_t sort_scratch_bytes) {
  const ScratchLayout layout(cells, line_nodes, a.capacity, sort_scratch_bytes);
  a.acceleration = at_offset<float>(base, layout.acceleration);
  a.shift = at_offset<float>(base, layout.shift);
  a.grip = at_offset<float>(base, layout.grip);
  a.neighbourhood = at_offset<std::uint32_t>(base, layout.neighbourhood);
  a.cell_key = at_offset<std::uint32_t>(base, layout.cell_key);
  a.sorted_key = at_offset<std::uint32_t>(base, layout.sorted_key);
  a.sorted_slot = at_offset<std::uint32_t>(base, layout.sorted_slot);
  a.sorted_position = at_offset<float>(base, layout.sorted_position);
  a.sorted_velocity = at_offset<float>(base, layout.sorted_velocity);
  a.sorted_birth = at_offset<std::uint32_t>(base, layout.sorted_birth);
  a.sorted_depth = at_offset<float>(base, layout.sorted_depth);
  a.line_weight = at_offset<float>(base, layout.line_weight);
  a.cell_start = at_offset<std::uint32_t>(base, layout.cell_start);
  a.fates = at_offset<AspiratedFates>(base, layout.fates);
  a.sort_scratch = sort_scratch_bytes ? at_offset<void>(base, layout.sort_scratch) : nullptr;
  a.sort_scratch_bytes = sort_scratch_bytes;
}

void clear_particles(Backend& backend, const ParticleArrays& a) {
  const std::size_t n = std::size_t(a.capacity);
  const std::vector<float> zeros(2 * n, 0.0f);
  backend.upload(a.position, zeros.data(), 2 * n * sizeof(float));
  backend.upload(a.velocity, zeros.data(), 2 * n * sizeof(float));
  backend.upload(a.anchor, zeros.data(), 2 * n * sizeof(float));
  backend.upload(a.acceleration, zeros.data(), 2 * n * sizeof(float));
  backend.upload(a.shift, zeros.data(), 2 * n * sizeof(float));
  backend.upload(a.grip, zeros.data(), n * sizeof(float));
  std::vector<std::uint32_t> words(n, 0u);
  backend.upload(a.neighbourhood, words.data(), n * sizeof(std::uint32_t));
  backend.upload(a.rest, words.data(), n * sizeof(std::uint32_t));
  std::fill(words.begin(), words.end(), kNeverUsed);
  backend.upload(a.age, words.data(), n * sizeof(std::uint32_t));
  const AspiratedFates none{};
  backend.upload(a.fates, &none, sizeof none);
  // The CUDA bin keeps its cells' counts at zero between steps (kernels/particles.cu).
  const std::vector<std::uint8_t> zero_bytes(a.sort_scratch_bytes, 0u);
  if (a.sort_scratch) backend.upload(a.sort_scratch, zero_bytes.data(), a.sort_scratch_bytes);
}

}  // namespace bleedsim
