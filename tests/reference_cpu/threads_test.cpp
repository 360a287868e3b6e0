// The CPU reference gives the same bytes at any thread count: every golden scene, frame by frame,
// at 1, 3 and 13 threads (neither 3 nor 13 divides the rows or the particles evenly, and 13 is more
// threads than CI's cores).
#include <gtest/gtest.h>

#include <filesystem>

#include "core/io/scenario.h"
#include "core/simulation/frame_hash.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

// Every field's hash, frame by frame, for the first `frames` frames (all of them by default).
std::vector<std::vector<std::pair<std::string, std::uint64_t>>> run_hashes(const std::string& scenario,
                                                                           int threads, int frames_wanted = -1) {
  Simulation sim(load_scenario(scenario).scene, BackendChoice{BackendChoice::Want::cpu, threads});
  std::vector<std::vector<std::pair<std::string, std::uint64_t>>> frames;
  const int count = frames_wanted < 0 ? sim.scene().frame_count() : frames_wanted;
  for (int k = 0; k < count; ++k) {
    sim.step();
    frames.push_back(hash_fields(sim));
  }
  return frames;
}

TEST(CpuThreads, EveryThreadCountGivesTheSameFrames) {
  int scenarios = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_dir() + "/scenarios/golden")) {
    const std::string scenario = entry.path().string();
    const auto one_thread = run_hashes(scenario, 1);
    for (const int threads : {3, 13})
      EXPECT_EQ(run_hashes(scenario, threads), one_thread) << scenario << " at " << threads << " threads";
    ++scenarios;
  }
  EXPECT_GE(scenarios, 3);
}

// The golden scenes hold too few particles to share the bin and the splat among threads (a thread
// takes 4096 at least): the hard case big-pile (100,000 emitted into 131,072 slots) over its first
// 12 frames, by when some 20,000 are alive, sorts them in up to 5 bands and splats them on as many.
TEST(CpuThreads, ManyParticlesSortAndSplatTheSameOnAnyThreads) {
  const std::string scenario = test::source_dir() + "/scenarios/hard/big-pile.toml";
  const auto one_thread = run_hashes(scenario, 1, 12);
  for (const int threads : {3, 5, 13}) EXPECT_EQ(run_hashes(scenario, threads, 12), one_thread) << threads << " threads";
}

}  // namespace
}  // namespace bleedsim