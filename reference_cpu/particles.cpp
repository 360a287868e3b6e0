// The CPU reference of the particle step: loops over core/physics/particles.h. The bin is a counting
// sort, which is stable, so it orders (cell, slot) exactly as the GPU's bin does.
#include <algorithm>
#include <cstring>
#include <vector>

#include "core/physics/particles.h"
#include "reference_cpu/parallel_rows.h"

namespace bleedsim {
namespace {

// The most the per-band cell counts of a parallel bin may take: a panel of many small cells sorts on
// one thread rather than hold a count per cell for every thread.
constexpr std::size_t kBinCountBytes = std::size_t(64) << 20;

// Only the live slots are sorted, as on the GPU. Aspirated particles in the live range carry the
// largest key, and sort after the living.
//
// A counting sort, stable: the live slots in ascending order are cut into bands, one a thread; each
// band counts its slots per cell; a cell's place is then the counts of the cells before it, and
// within the cell, of the bands before this one; each band writes its slots there in its own order.
// So every cell holds its slots in ascending slot order, the serial sort's order, on any number of
// threads.
void bin(const ParticleArgs& a, int threads) {
  const ParticleArrays& p = a.arrays;
  const ParticleModel& m = a.model;
  const std::uint32_t cells = cell_count(m), none = sentinel_key(m);
  const int n = a.live_count;
  const int bands = std::max(1, std::min(threads_for_particles(n, threads),
                                         int(kBinCountBytes / (sizeof(std::uint32_t) * std::max<std::uint32_t>(cells, 1)))));
  // counts[b · cells + c]: band b's slots in cell c, then where band b writes its next slot of c.
  // Kept from step to step by the calling thread (the bands on other threads reach it through
  // this reference: a thread_local named inside them would be their own).
  static thread_local std::vector<std::uint32_t> kept_counts;
  std::vector<std::uint32_t>& counts = kept_counts;
  counts.resize(std::size_t(bands) * cells);
  const auto band_first = [&](int band) { return int(std::int64_t(n) * band / bands); };
  parallel_rows(bands, bands, [&](int band) {
    std::uint32_t* count = counts.data() + std::size_t(band) * cells;
    std::fill(count, count + cells, 0u);
    for (int t = band_first(band); t < band_first(band + 1); ++t) {
      const int slot = nth_live_slot_ascending(a, t);
      p.cell_key[slot] = cell_key_of(p, m, slot);
      if (p.cell_key[slot] != none) ++count[p.cell_key[slot]];
    }
  });
  // Each cell's start and end; within it, each band's first place. Cells in chunks over the threads:
  // each chunk's total first, then their running sum, then each chunk's cells from its start.
  const int chunks = std::max(1, std::min(threads, int(cells / 4096)));
  const auto chunk_first = [&](int chunk) { return std::uint32_t(std::uint64_t(cells) * chunk / chunks); };
  std::vector<std::uint32_t> chunk_start(chunks + 1, 0u);
  parallel_rows(chunks, chunks, [&](int chunk) {
    std::uint32_t total = 0;
    for (int band = 0; band < bands; ++band) {
      const std::uint32_t* count = counts.data() + std::size_t(band) * cells;
      for (std::uint32_t c = chunk_first(chunk); c < chunk_first(chunk + 1); ++c) total += count[c];
    }
    chunk_start[chunk + 1] = total;
  });
  for (int chunk = 0; chunk < chunks; ++chunk) chunk_start[chunk + 1] += chunk_start[chunk];
  parallel_rows(chunks, chunks, [&](int chunk) {
    std::uint32_t at = chunk_start[chunk];
    for (std::uint32_t c = chunk_first(chunk); c < chunk_first(chunk + 1); ++c) {
      p.cell_start[c] = at;
      for (int band = 0; band < bands; ++band) {
        std::uint32_t& count = counts[std::size_t(band) * cells + c];
        const std::uint32_t in_band = count;
        count = at;
        at += in_band;
      }
    }
  });
  const int living = int(chunk_start[chunks]);
  p.cell_start[cells] = std::uint32_t(living);
  parallel_rows(bands, bands, [&](int band) {
    std::uint32_t* next = counts.data() + std::size_t(band) * cells;
    for (int t = band_first(band); t < band_first(band + 1); ++t) {
      const int slot = nth_live_slot_ascending(a, t);
      if (p.cell_key[slot] == none) continue;
      const std::uint32_t to = next[p.cell_key[slot]]++;
      p.sorted_key[to] = p.cell_key[slot];
      p.sorted_slot[to] = std::uint32_t(slot);
    }
  });
  std::fill(p.sorted_key + living, p.sorted_key + n, none);
  parallel_rows(living, threads_for_particles(living, threads), [&](int i) { gather_sorted(p, i); });
}

}  // namespace

void cpu_twin(ParticlePhase phase, const ParticleArgs& a, int threads) {
  const int n = a.live_count;
  switch (phase) {
    case ParticlePhase::emit:
      for (int t = 0; t < a.new_count; ++t) emit_particle(a, t);
      break;
    case ParticlePhase::bin:
      bin(a, threads);
      break;
    case ParticlePhase::collide:
      parallel_rows(n, threads_for_particles(n, threads), [&](int i) { collide_particle(a.arrays, a.model, i); });
      break;
    case ParticlePhase::integrate:
      parallel_rows(n, threads_for_particles(n, threads), [&](int t) { integrate_particle(a.arrays, a.model, live_slot(a, t)); });
      break;
  }
}

void cpu_twin(const ParticleSteps& f, int threads) {
  for (int s = 0; s < f.count; ++s)
    for (const ParticlePhase phase : {ParticlePhase::emit, ParticlePhase::bin, ParticlePhase::collide, ParticlePhase::integrate})
      cpu_twin(phase, args_at(f.base, f.steps[s], f.emitters, phase), threads);
}

}  // namespace bleedsim
