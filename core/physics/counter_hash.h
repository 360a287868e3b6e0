#pragma once
// Random numbers that both backends draw alike: a counter-based hash of (seed, particle id, step,
// stream), integer operations only, so a number depends on what it is for, never on the order in
// which threads ask for it.
#include <cstdint>

#include "core/physics/hd.h"

namespace bleedsim {

// Chris Wellons' "lowbias32" integer finaliser: every input bit affects every output bit.
BLEEDSIM_HD inline std::uint32_t mix32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

BLEEDSIM_HD inline std::uint32_t counter_hash(std::uint64_t seed, std::uint64_t id, std::uint64_t step,
                                             std::uint32_t stream) {
  std::uint32_t h = mix32(static_cast<std::uint32_t>(seed) ^ 0x9e3779b9U);
  h = mix32(h ^ static_cast<std::uint32_t>(seed >> 32));
  h = mix32(h ^ static_cast<std::uint32_t>(id));
  h = mix32(h ^ static_cast<std::uint32_t>(id >> 32));
  h = mix32(h ^ static_cast<std::uint32_t>(step));
  h = mix32(h ^ static_cast<std::uint32_t>(step >> 32));
  return mix32(h ^ stream);
}

// Coordinate `axis` (0 or 1) of point `id` of the R2 sequence (M. Roberts 2018, "The unreasonable
// effectiveness of quasirandom sequences": the Kronecker sequence of the plastic number, the 2D one
// whose points keep farthest apart), in 32-bit fixed point and turned by a seed's hash. Any run of
// n consecutive ids covers the unit square about as evenly as a lattice of n points, where n
// independent draws leave clumps and gaps.
BLEEDSIM_HD inline std::uint32_t even_point(std::uint64_t seed, std::uint64_t id, std::uint32_t axis) {
  const std::uint32_t step = axis == 0 ? 0xc13fa9a9U : 0x91e10da6U;  // 2³²/φ₂ and 2³²/φ₂², φ₂ the plastic number
  return counter_hash(seed, 0, 0, 0x52320000U + axis) + static_cast<std::uint32_t>(id) * step;
}

// A hash as a float in [-1, 1): its top 24 bits scaled exactly (no rounding on either backend).
BLEEDSIM_HD inline float signed_unit(std::uint32_t h) {
  return static_cast<float>(h >> 8) * (2.0f / 16777216.0f) - 1.0f;
}

}  // namespace bleedsim
