// bleedsim study as a user runs it, on a scene small enough for CI: the CSV, the HDF5 file and the
// plots written; bad knobs refused with exit 2 and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/effects/particle_model.h"
#include "core/io/scenario.h"
#include "tests/cli/cli_harness.h"

namespace bleedsim::test {
namespace {

namespace fs = std::filesystem;

// Spread, particles and blur on a 32 × 24 px panel, 0.2 s (6 frames).
fs::path tiny_scene(const fs::path& folder) {
  write_text(folder / "tiny.toml",
             "[scene]\nname = \"tiny\"\nwidth_px = 32\nheight_px = 24\nwidth_mm = 8.0\nheight_mm = 6.0\n"
             "duration_s = 0.2\n[spread]\nradius_mm = 2.0\n[particles]\ncapacity = 1024\nflow_mm3_per_s_per_mm = 3.2\n"
             "[blur]\n[[cut]]\nx_mm = 4.0\ny_mm = 2.0\n");
  return folder / "tiny.toml";
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(StudyCommand, WritesTheTableTheDetailsAndThePlots) {
  const fs::path folder = scratch_folder();
  const fs::path out = folder / "study";
  // The scene's own sub-steps: the fewest its contact allows; the study tries twice as many too.
  const Scene scene = load_scenario(tiny_scene(folder).string()).scene;
  const int fewest = particle_mechanics(*scene.particles, scene.domain, scene.frame_rate_hz).substeps;
  const CliResult result = run_cli("study '" + tiny_scene(folder).string() + "' --knob substeps=" +
                                   std::to_string(2 * fewest) + " --knob resolution=0.5,1 --backend cpu --out '" +
                                   out.string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("tiny: 6 settings on 1 backend(s), 6 frames each; reference: substeps " +
                               std::to_string(2 * fewest) + ", resolution 1; compared on 16 x 12 cells"),
            std::string::npos)
      << result.output;
  const std::vector<std::string> csv = lines_of(read_bytes(out / "study.csv"));
  ASSERT_EQ(csv.size(), 7u) << read_bytes(out / "study.csv");  // header, reference, check, 2 + 2 settings
  EXPECT_EQ(csv[0].rfind("scene,knob,value,role,backend,status,frames,ms_per_frame_p50", 0), 0u);
  EXPECT_EQ(csv[1].rfind("tiny,reference,0,reference,cpu,ok,6,", 0), 0u) << csv[1];
  EXPECT_EQ(csv[3].rfind("tiny,substeps," + std::to_string(fewest) + ",base,cpu,ok,6,", 0), 0u) << csv[3];
  EXPECT_EQ(csv[6].rfind("tiny,resolution,1,base,cpu,ok,6,", 0), 0u) << csv[6];
  EXPECT_TRUE(fs::exists(out / "study.h5"));
  // The plots, where Debian's matplotlib is (scripts/setup installs it).
  if (run_shell("'" + python() + "' -c 'import matplotlib'").exit_code != 0)
    GTEST_SKIP() << "plots NOT checked: " << python() << " has no matplotlib";
  EXPECT_TRUE(fs::exists(out / "plots" / "pareto.png")) << result.output;
  EXPECT_TRUE(fs::exists(out / "plots" / "substeps.png")) << result.output;
  EXPECT_TRUE(fs::exists(out / "plots" / "resolution.png")) << result.output;
}

TEST(StudyCommand, BadKnobsExitTwoAndWriteNothing) {
  const fs::path folder = scratch_folder();
  const fs::path scene = tiny_scene(folder);
  const struct {
    const char* knob;
    const char* message;
  } cases[] = {{"substep=1,2", "--knob: no knob 'substep' (known: compression, substeps, particle_size,"},
               {"substeps", "--knob: write it as substeps=v1,v2,... (got 'substeps')"},
               {"substeps=20,x", "--knob substeps: expected numbers separated by commas, got 'x'"},
               {"blur_downsample=3", "--knob blur_downsample: values of blur.downsample must be 1, 2 or 4 (got 3)"}};
  for (const auto& c : cases) {
    const CliResult result = run_cli("study '" + scene.string() + "' --knob " + c.knob + " --backend cpu --out '" +
                                     (folder / "out").string() + "'");
    EXPECT_EQ(result.exit_code, 2) << c.knob << ": " << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(folder / "out")) << c.knob;
  }
}

}  // namespace
}  // namespace bleedsim::test
