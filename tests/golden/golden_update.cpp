// Regenerates one golden scene on the CPU reference (run by scripts/update-goldens).
// Usage: golden_update <scenario.toml> <golden folder>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "core/io/scenario.h"
#include "core/simulation/frame_hash.h"
#include "tests/golden/golden.h"

int main(int argc, char** argv) {
  using namespace bleedsim;
  if (argc != 3) {
    std::fprintf(stderr, "usage: golden_update <scenario.toml> <golden folder>\n");
    return 2;
  }
  try {
    const std::string scenario = argv[1], dir = argv[2];
    Simulation sim(load_scenario(scenario).scene, BackendChoice{BackendChoice::Want::cpu, 0});
    const long frames = sim.scene().frame_count();
    const std::vector<long> keys = golden::key_frame_numbers(frames);
    std::vector<golden::FieldHashes> hashes;
    std::map<long, golden::FieldBytes> key_frames;
    std::vector<HapticTick> ticks;
    for (long k = 0; k < frames; ++k) {
      sim.step();
      ticks.insert(ticks.end(), sim.haptic_ticks().begin(), sim.haptic_ticks().end());
      hashes.push_back(hash_fields(sim));
      if (std::find(keys.begin(), keys.end(), k) != keys.end())
        for (const std::string& name : sim.field_names()) key_frames[k][name] = sim.copy_field(name);
    }
    std::filesystem::create_directories(dir);
    golden::write_hashes(dir, scenario, hashes);
    golden::write_key_frames(dir, sim, key_frames, ticks);
    std::printf("%s: %ld frames, %zu key frames -> %s\n", scenario.c_str(), frames, key_frames.size(), dir.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "golden_update: %s\n", e.what());
    return 1;
  }
  return 0;
}
