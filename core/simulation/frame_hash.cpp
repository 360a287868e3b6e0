#include "core/simulation/frame_hash.h"

#include "core/haptics/haptic_channel.h"
#include "core/runtime/hash.h"

namespace bleedsim {

std::vector<std::pair<std::string, std::uint64_t>> hash_fields(const Simulation& simulation) {
  std::vector<std::pair<std::string, std::uint64_t>> hashes;
  for (const std::string& name : simulation.field_names()) {
    const std::vector<std::uint8_t> bytes = simulation.copy_field(name);
    hashes.emplace_back(name, fnv1a64(bytes.data(), bytes.size()));
  }
  if (simulation.scene().trace) hashes.emplace_back("haptics", haptic_channel_hash(simulation.haptic_ticks()));
  return hashes;
}

}  // namespace bleedsim
