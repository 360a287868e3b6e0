// The CPU reference of the particle step: loops over core/particles.h. The sort is a counting
// sort, which is stable, so it orders (cell, slot) exactly as the GPU's radix sort does.
#include <algorithm>
#include <cstring>

#include "core/particles.h"
#include "reference_cpu/parallel_rows.h"

namespace bleedsim {
namespace {

// Fewer particles than this are not worth starting threads for.
constexpr int kParticlesPerThread = 4096;

int threads_for(int count, int threads) { return std::max(1, std::min(threads, count / kParticlesPerThread)); }

void bin(const ParticleArgs& a) {
  const ParticleArrays& p = a.arrays;
  const ParticleModel& m = a.model;
  const std::uint32_t cells = std::uint32_t(m.cells_x) * std::uint32_t(m.cells_y);
  // Count per cell, then each cell's start; cell_end serves as the write cursor and ends as the end.
  std::fill(p.cell_end, p.cell_end + cells, 0u);
  for (int slot = 0; slot < p.capacity; ++slot) {
    p.cell_key[slot] = cell_key_of(p, m, slot);
    if (p.cell_key[slot] != cells) ++p.cell_end[p.cell_key[slot]];
  }
  std::uint32_t at = 0;
  for (std::uint32_t c = 0; c < cells; ++c) {
    p.cell_start[c] = at;
    at += p.cell_end[c];
    p.cell_end[c] = p.cell_start[c];
  }
  std::uint32_t dead_at = at;  // slots with no particle follow, in slot order, as a stable sort leaves them
  for (int slot = 0; slot < p.capacity; ++slot) {
    const std::uint32_t key = p.cell_key[slot];
    const std::uint32_t to = key != cells ? p.cell_end[key]++ : dead_at++;
    p.sorted_key[to] = key;
    p.sorted_slot[to] = std::uint32_t(slot);
  }
  for (int i = 0; i < p.capacity; ++i) gather_sorted(p, i);
}

void draw(const ParticleArgs& a) {
  std::fill(a.cover, a.cover + std::size_t(a.grid.width) * std::size_t(a.grid.height), 0.0f);
  for (int slot = 0; slot < a.arrays.capacity; ++slot)
    draw_particle(a.arrays, a.model, a.grid, slot,
                  [&](std::size_t pixel, float alpha) { a.cover[pixel] = std::max(a.cover[pixel], alpha); });
}

}  // namespace

void particles_cpu(ParticlePhase phase, const ParticleArgs& a, int threads) {
  const int n = a.arrays.capacity;
  switch (phase) {
    case ParticlePhase::emit:
      for (int t = 0; t < a.new_count; ++t) emit_particle(a, t);
      break;
    case ParticlePhase::bin:
      bin(a);
      break;
    case ParticlePhase::collide:
      parallel_rows(n, threads_for(n, threads), [&](int i) { collide_particle(a.arrays, a.model, i); });
      break;
    case ParticlePhase::integrate:
      parallel_rows(n, threads_for(n, threads), [&](int slot) { integrate_particle(a.arrays, a.model, slot); });
      break;
    case ParticlePhase::draw:
      draw(a);
      break;
  }
}

}  // namespace bleedsim
