#pragma once
// Golden scenes: golden/<scene>/hashes.txt pins every frame's per-field FNV-1a 64, and
// golden/<scene>/keyframes.h5 keeps a few whole frames for diagnosing a mismatch (and the haptic
// channel of a scene that replays a trace, for the independent check).
// Scenario files live in scenarios/golden/<scene>.toml.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/simulation/simulation.h"

namespace bleedsim::golden {

using FieldHashes = std::vector<std::pair<std::string, std::uint64_t>>;
using FieldBytes = std::map<std::string, std::vector<std::uint8_t>>;

std::vector<std::string> scenes();  // every folder under golden/, sorted
std::string scenario_path(const std::string& scene);
std::string golden_dir(const std::string& scene);

// Throws std::runtime_error naming the file when it is missing or malformed.
std::vector<FieldHashes> read_hashes(const std::string& dir);
void write_hashes(const std::string& dir, const std::string& scenario,
                  const std::vector<FieldHashes>& frames);

// The frames kept whole: at the start, a third and two thirds in, and the last.
std::vector<long> key_frame_numbers(long frame_count);
std::map<long, FieldBytes> read_key_frames(const std::string& dir);
// Writes keyframes.h5 with every field of the simulation at the given frames and, for a scene that
// replays a trace, the whole run's haptic channel (/haptics, every tick).
void write_key_frames(const std::string& dir, const Simulation& simulation,
                      const std::map<long, FieldBytes>& frames, const std::vector<HapticTick>& ticks);

}  // namespace bleedsim::golden
