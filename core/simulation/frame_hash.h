#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/simulation/simulation.h"

namespace bleedsim {

// FNV-1a 64 of each field's bytes in the last computed frame, in field order: the fingerprint that
// goldens pin and that two backends or two thread counts must agree on. A scene that replays a
// trace adds "haptics": the hash of the frame's haptic ticks (core/haptics/haptic_channel.h).
std::vector<std::pair<std::string, std::uint64_t>> hash_fields(const Simulation& simulation);

}  // namespace bleedsim
