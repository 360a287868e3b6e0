// Golden frames: every golden scene, on the CPU reference and on the CUDA backend, must give
// exactly the pinned per-frame hashes. On a mismatch the failure names the first differing frame
// and field, and compares the nearest key frame pixel by pixel, with diff images in the build tree.
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <sstream>

#include "core/io/scenario.h"
#include "core/runtime/hash.h"
#include "core/simulation/frame_hash.h"
#include "tests/golden/frame_diff.h"
#include "tests/golden/golden.h"
#include "tests/test_paths.h"

namespace bleedsim::golden {
namespace {

using Want = BackendChoice::Want;

struct FirstMismatch {
  long frame;
  std::string field;
  std::uint64_t got, expected;
};

std::optional<FirstMismatch> compare(long frame, const FieldHashes& got, const FieldHashes& expected) {
  for (const auto& [name, hash] : got) {
    const auto it = std::find_if(expected.begin(), expected.end(), [&](const auto& e) { return e.first == name; });
    if (it == expected.end()) return FirstMismatch{frame, name + " (not in the golden)", hash, 0};
    if (it->second != hash) return FirstMismatch{frame, name, hash, it->second};
  }
  if (got.size() != expected.size()) return FirstMismatch{frame, "(field list differs from the golden)", 0, 0};
  return std::nullopt;
}

// Pixel-level account of the first key frame at or after the first mismatch.
std::string diagnose(const Simulation& sim, const std::string& scene, const std::string& backend,
                     const FirstMismatch& first, const std::map<long, FieldBytes>& actual,
                     const std::map<long, FieldBytes>& expected) {
  std::ostringstream report;
  report << scene << " on " << backend << ": first differing frame " << first.frame << ", field "
         << first.field << ": hash " << hex64(first.got) << ", golden " << hex64(first.expected) << "\n";
  const auto key = expected.lower_bound(first.frame);
  if (key == expected.end() || !actual.count(key->first)) return report.str();
  const std::string folder = test::binary_dir() + "/golden-diff/" + scene + "-" + backend;
  std::filesystem::create_directories(folder);
  for (const auto& [name, want] : key->second) {
    const FieldLayout& layout = *sim.field(name).field;
    const std::vector<std::uint8_t>& got = actual.at(key->first).at(name);
    const DiffStats stats = diff_field(layout, want, got);
    report << "  key frame " << key->first << ", " << name << ": " << describe(layout, stats) << "\n";
    if (stats.differing == 0) continue;
    std::string stem = name;
    std::replace(stem.begin(), stem.end(), '/', '-');
    write_diff_images(folder + "/frame" + std::to_string(key->first) + "-" + stem + "-", layout, want, got);
  }
  report << "  diff images: " << folder << "/";
  return report.str();
}

struct GoldenCase {
  std::string scene;
  Want backend;
};

const char* backend_name(Want backend) { return backend == Want::cuda ? "cuda" : "cpu"; }

void PrintTo(const GoldenCase& c, std::ostream* out) { *out << c.scene << " on " << backend_name(c.backend); }

class Golden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(Golden, EveryFrameMatchesItsPinnedHash) {
  const GoldenCase& c = GetParam();
  const std::string backend = backend_name(c.backend);
  if (c.backend == Want::cuda) {
    std::string why_not;
    if (!cuda_device_available(&why_not)) GTEST_SKIP() << "GPU parity NOT checked: " << why_not;
  }
  const std::vector<FieldHashes> pinned = read_hashes(golden_dir(c.scene));
  const std::map<long, FieldBytes> key_frames = read_key_frames(golden_dir(c.scene));
  Simulation sim(load_scenario(scenario_path(c.scene)).scene, BackendChoice{c.backend, 0});
  ASSERT_EQ(std::size_t(sim.scene().frame_count()), pinned.size()) << "frame count differs from the golden";

  std::optional<FirstMismatch> first;
  std::map<long, FieldBytes> actual;
  for (long k = 0; k < long(pinned.size()); ++k) {
    sim.step();
    if (!first) first = compare(k, hash_fields(sim), pinned[k]);
    if (first && key_frames.count(k))
      for (const std::string& name : sim.field_names()) actual[k][name] = sim.copy_field(name);
  }
  if (first) FAIL() << diagnose(sim, c.scene, backend, *first, actual, key_frames);
}

std::vector<GoldenCase> cases(Want backend) {
  std::vector<GoldenCase> all;
  for (const std::string& scene : scenes()) all.push_back({scene, backend});
  return all;
}

std::string case_name(const ::testing::TestParamInfo<GoldenCase>& info) {
  std::string name = info.param.scene;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

TEST(GoldenSuite, EveryGoldenScenarioHasItsGoldenAndThereAreAtLeastThree) {
  std::vector<std::string> scenarios;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_dir() + "/scenarios/golden"))
    scenarios.push_back(entry.path().stem().string());
  std::sort(scenarios.begin(), scenarios.end());
  EXPECT_EQ(scenarios, scenes()) << "scenarios/golden/*.toml and golden/*/ must name the same scenes";
  EXPECT_GE(scenes().size(), 3u);
}

INSTANTIATE_TEST_SUITE_P(Cpu, Golden, ::testing::ValuesIn(cases(Want::cpu)), case_name);
INSTANTIATE_TEST_SUITE_P(Cuda, Golden, ::testing::ValuesIn(cases(Want::cuda)), case_name);

}  // namespace
}  // namespace bleedsim::golden
