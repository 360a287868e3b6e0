// The CPU reference of the suction: loops over core/physics/instrument.h. Nearest first is a
// partial sort (nth_element) of the candidates' keys: they are unique, so it selects the same set
// as the GPU's radix select.
#include <algorithm>

#include "core/physics/instrument.h"

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

void cpu_twin(const InstrumentArgs& suction, int) { aspirate_nearest(suction); }

}  // namespace bleedsim
