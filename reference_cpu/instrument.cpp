// The CPU reference of the instrument: loops over core/physics/instrument.h. Nearest first is a
// partial sort (nth_element) of the candidates' keys: they are unique, so it selects the same set
// as the GPU's radix select.
#include <algorithm>

#include "core/physics/instrument.h"
#include "reference_cpu/parallel_rows.h"

namespace bleedsim {
namespace {

void aspirate_nearest(const InstrumentArgs& a) {
  std::uint64_t* keys = a.candidates;
  std::uint32_t n = 0;
  for (int t = 0; t < a.live_count; ++t) {
    const std::uint64_t key = aspiration_key(a, live_slot(a, t));
    if (key != kNoCandidate) keys[n++] = key;
  }
  const std::uint32_t take = std::min(n, a.quota);
  if (take == 0) return;
  if (take < n) std::nth_element(keys, keys + (take - 1), keys + n);
  for (std::uint32_t i = 0; i < take; ++i) aspirate(a.arrays, keys[i]);
  a.arrays.fates->aspirated += take;
}

}  // namespace

void cpu_twin(InstrumentPhase phase, const InstrumentArgs& a, int threads) {
  switch (phase) {
    case InstrumentPhase::aspirate:
      aspirate_nearest(a);
      break;
    case InstrumentPhase::contact:
      // Each particle moves only itself: any thread count gives the same bytes.
      parallel_rows(a.live_count, threads_for_particles(a.live_count, threads),
                    [&](int t) { keep_out_of_tip(a, live_slot(a, t)); });
      break;
  }
}

}  // namespace bleedsim
