// bleedsim run and bleedsim trace quality on scenarios that replay a Falcon trace, as a user runs
// them: the haptic channel and its quality in the HDF5 file, the budgets in the summary, the quality
// table, and every kind of bad trace refused with its line and exit 2 before anything is written.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "tests/cli/cli_harness.h"

namespace bleedsim::test {
namespace {

namespace fs = std::filesystem;

TEST(RunHaptics, WritesTheHapticChannelAndReportsTheBudgets) {
  BLEEDSIM_SKIP_UNLESS_H5PY();
  // The example stroke (scenarios/traces/single-stroke.csv) over a small panel for 4.2 s.
  const fs::path folder = scratch_folder();
  const std::string trace = source_dir() + "/scenarios/traces/single-stroke.csv";
  write_text(folder / "stroke.toml",
             "[scene]\nwidth_px = 64\nheight_px = 48\nwidth_mm = 32.0\nheight_mm = 24.0\nduration_s = 4.2\n"
             "[spread]\nradius_mm = 2.0\n[particles]\ncapacity = 4096\nflow_mm3_per_s_per_mm = 0.2\nbleed_s = 1.0\n"
             "[haptics]\ntrace = \"" + trace + "\"\ncut_spacing_mm = 1.5\n"
             "[output]\ndir = \"" + (folder / "out").string() + "\"\n");
  const CliResult result = run_cli("run '" + (folder / "stroke.toml").string() + "' --backend cpu");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // Read as far as the run goes: ticks to 4.2 s, and the first sample past it.
  EXPECT_NE(result.output.find("replaying " + trace + ": 4202 samples over 4.201 s through the 1 kHz haptic loop "
                               "(read as far as the run goes)"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("of 126 frames: p99 is"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("of 4201 ticks: p99 is"), std::string::npos) << result.output;
  // The stroke: 1.0 to 3.83 s at 10 mm/s along 25.3 mm, a cut at once and every 1.5 mm after.
  // (The timings themselves vary with the machine's load; only their presence is checked.)
  EXPECT_NE(result.output.find("; 17 cuts made\n"), std::string::npos) << result.output;
  // The file as h5py sees it: /haptics, one row per tick (4.2 s at 1 kHz, ticks 0..4200), its force
  // along the normal only, within [0, 8] N, zero out of contact, cutting only in contact.
  const CliResult check = run_shell("'" + python() + "' '" + source_dir() + "/tests/check_hdf5_layout.py' '" +
                                    (folder / "out" / "frames.h5").string() +
                                    "' --frames 126 --fields spread/stain,splat/thickness --arrays particles/accounting"
                                    " --haptics 4201 --max-force 8");
  EXPECT_EQ(check.exit_code, 0) << check.output;
}

TEST(RunHaptics, ValidateReplaysTheStylusAlone) {
  // The example stroke over the example scene: 6 s of ticks, the contact and the cuts it makes.
  const CliResult result = run_cli("validate '" + source_dir() + "/scenarios/falcon-stroke.toml'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("haptics    surface z = 120 mm; k 500 N/m, b 0.5 N·s/m, cap 8 N; passive: "
                               "k·T/2 + |b| = 0.75 < 1.5 N·s/m"),
            std::string::npos)
      << result.output;
  // 6001 ticks (0..6000 ms); the stroke is in contact from 1.004 s until the lift; 25.3 mm at
  // a cut per mm and one at once: 26 cuts.
  EXPECT_NE(result.output.find("stylus     6001 ticks: in contact 2891, cutting 2826; 26 cuts; peak force 1.05 N"),
            std::string::npos)
      << result.output;
}

// A scenario whose [haptics] trace is `trace`, in a scratch folder; returns the scenario's path.
fs::path scenario_with_trace(const fs::path& folder, const std::string& trace) {
  write_text(folder / "t.csv", trace);
  write_text(folder / "s.toml",
             "[scene]\nwidth_px = 32\nheight_px = 24\nwidth_mm = 32.0\nheight_mm = 24.0\nduration_s = 0.1\n"
             "[spread]\n[haptics]\ntrace = \"t.csv\"\n[output]\ndir = \"" + (folder / "out").string() + "\"\n");
  return folder / "s.toml";
}

struct BadTrace {
  const char* name;
  std::string text;
  std::string message;  // what the error must say, from the file name on
};

const std::string kMetadata = "# device: Novint Falcon\n# frame: libnifalcon\n# rate_hz: 1000\n";
const std::string kHeader = "t_s,x_m,y_m,z_m,buttons\n";
const std::string kTwoSamples = "0.000,0.0,0.0,0.1200,0\n0.001,0.0,0.0,0.1190,1\n";

class RunBadTrace : public ::testing::TestWithParam<BadTrace> {};

// bleedsim run, and bleedsim trace quality alike.
TEST_P(RunBadTrace, ExitsTwoNamingTheLineAndWritesNothing) {
  const BadTrace& bad = GetParam();
  const fs::path folder = scratch_folder();
  const std::string scenario = "'" + scenario_with_trace(folder, bad.text).string() + "'";
  for (const std::string& command : {"run " + scenario + " --backend cpu", "trace quality " + scenario}) {
    const CliResult result = run_cli(command);
    EXPECT_EQ(result.exit_code, 2) << command << "\n" << result.output;
    EXPECT_NE(result.output.find("bleedsim: error: " + (folder / "t.csv").string() + bad.message), std::string::npos)
        << command << "\n" << result.output;
    EXPECT_FALSE(fs::exists(folder / "out")) << "a bad trace must leave no output";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Traces, RunBadTrace,
    ::testing::Values(
        BadTrace{"Empty", "", ": the file is empty"},
        BadTrace{"WrongHeader", kMetadata + "time,x,y,z,buttons\n" + kTwoSamples, ":4:6: header: column 2 is 'x'"},
        BadTrace{"WrongUnits", kMetadata + "t_s,x_mm,y_mm,z_mm,buttons\n" + kTwoSamples,
                 ":4:5: header: column 2 is 'x_mm': positions are in metres (x_m)"},
        BadTrace{"TimeNotIncreasing", kMetadata + kHeader + kTwoSamples + "0.001,0.0,0.0,0.1190,1\n",
                 ":7:1: t_s: time must be strictly increasing"},
        BadTrace{"NaN", kMetadata + kHeader + kTwoSamples + "0.002,nan,0.0,0.1190,1\n",
                 ":7:7: x_m: must be a finite number (got nan)"},
        BadTrace{"OutsideTheWorkspace", kMetadata + kHeader + kTwoSamples + "0.002,0.0,0.0,119.0,1\n",
                 ":7:15: z_m: 119 m is outside the Falcon's workspace"}),
    [](const ::testing::TestParamInfo<BadTrace>& info) { return std::string(info.param.name); });

TEST(RunHaptics, AMissingTraceIsPlacedAtTheScenarioKey) {
  const fs::path folder = scratch_folder();
  const fs::path scenario = scenario_with_trace(folder, "");
  fs::remove(folder / "t.csv");
  const CliResult result = run_cli("run '" + scenario.string() + "' --backend cpu");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find(scenario.string() + ":9:9: haptics.trace: cannot read trace file '" +
                               (folder / "t.csv").string() + "': No such file or directory"),
            std::string::npos)
      << result.output;
}

// "  in contact N," of bleedsim validate's stylus line: the ticks in contact, counted by the loop alone.
long validate_contact_ticks(const std::string& output) {
  const std::size_t at = output.find("in contact ");
  return at == std::string::npos ? -1 : std::stol(output.substr(at + 11));
}

TEST(TraceQuality, ItsContactsAreTheTicksValidateCountsInContact) {
  // The golden strokes: three strokes, each one contact. The rows' tick counts (column 3) sum to the
  // ticks validate finds in contact over the same run, and every contact is passive (k·T/2 + b = 1.2
  // < 1.5 N·s/m: Colgate & Schenkel's bound holds for any motion).
  const std::string scenario = source_dir() + "/scenarios/golden/falcon-strokes.toml";
  const CliResult result = run_cli("trace quality '" + scenario + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("falcon-strokes replays"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("k 800 N/m, b 0.8 N·s/m, cap 8 N; device damping B 1.5 N·s/m"), std::string::npos)
      << result.output;
  long rows = 0, ticks = 0;
  for (int number = 1;; ++number) {
    char prefix[16];
    std::snprintf(prefix, sizeof prefix, "\n  %3d  ", number);
    const std::size_t at = result.output.find(prefix);
    if (at == std::string::npos) break;
    ++rows;
    ticks += std::stol(result.output.substr(result.output.find_first_of(" *", at + 26) + 1));
  }
  EXPECT_EQ(rows, 3) << result.output;
  const CliResult validate = run_cli("validate '" + scenario + "'");
  ASSERT_EQ(validate.exit_code, 0) << validate.output;
  EXPECT_EQ(ticks, validate_contact_ticks(validate.output)) << result.output << validate.output;
  EXPECT_NE(result.output.find("passive: D - W >= 0 at every tick of every contact"), std::string::npos) << result.output;
}

TEST(TraceQuality, AContactTooShortForAMetricSaysWhy) {
  // Down 1 mm for one sample (one tick in contact), then above the surface again: no rise, too short
  // for the spectrum; the run (0.1 s) ends above the tissue.
  const fs::path folder = scratch_folder();
  const fs::path scenario = scenario_with_trace(
      folder, kMetadata + kHeader + "0.000,0.0,0.0,0.1210,0\n0.001,0.0,0.0,0.1190,0\n0.002,0.0,0.0,0.1210,0\n");
  const CliResult result = run_cli("trace quality '" + scenario.string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("contact 1, rise_time: a contact of 1 tick: the force has no rise to measure"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("contact 1, oscillation_rms: a contact of 1 tick is shorter than one period of the 30 Hz "
                               "cutoff (34 ticks)"),
            std::string::npos)
      << result.output;
}

TEST(TraceQuality, RefusesAScenarioWithoutATraceAndSettingsARunRefuses) {
  const fs::path folder = scratch_folder();
  write_text(folder / "plain.toml", "[scene]\nwidth_px = 32\nheight_px = 24\nwidth_mm = 32.0\nheight_mm = 24.0\nduration_s = 0.1\n[spread]\n");
  const CliResult plain = run_cli("trace quality '" + (folder / "plain.toml").string() + "'");
  EXPECT_EQ(plain.exit_code, 2) << plain.output;
  EXPECT_NE(plain.output.find("bleedsim: error: " + (folder / "plain.toml").string() +
                              ": haptics: the scenario replays no trace"),
            std::string::npos)
      << plain.output;
  // Too stiff a spring for the device's damping: refused at its key, as a run refuses it.
  const fs::path scenario = scenario_with_trace(folder, kMetadata + kHeader + kTwoSamples);
  const CliResult stiff = run_cli("trace quality '" + scenario.string() + "' --set haptics.stiffness_N_per_m=3000");
  EXPECT_EQ(stiff.exit_code, 2) << stiff.output;
  EXPECT_NE(stiff.output.find("haptics.stiffness_N_per_m: k·T/2 + |b| = 1.5 + 0.5 = 2 N·s/m is not below"),
            std::string::npos)
      << stiff.output;
}

}  // namespace
}  // namespace bleedsim::test
