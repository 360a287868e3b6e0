// bleedsim trace info and trace synth, as a user runs them: a good trace described, a bad one refused
// with its line; a synthesised trace written whole, never over a file unasked, nothing written on bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>

#include "tests/cli/cli_harness.h"

namespace bleedsim::test {
namespace {

// Two presses of the cutting button and a 3 ms dropout between lines 9 and 10.
const std::string kTrace =
    "# device: Novint Falcon\n"
    "# frame: libnifalcon\n"
    "# rate_hz: 1000\n"
    "t_s,x_m,y_m,z_m,buttons\n"
    "0.000,0.0100,-0.0050,0.1200,0\n"
    "0.001,0.0101,-0.0050,0.1199,1\n"
    "0.002,0.0102,-0.0051,0.1198,1\n"
    "0.003,0.0103,-0.0051,0.1197,0\n"
    "0.004,0.0104,-0.0052,0.1196,0\n"
    "0.007,0.0107,-0.0052,0.1195,1\n"
    "0.008,0.0108,-0.0052,0.1195,1\n";

TEST(TraceInfo, DescribesATraceItsCutsAndItsRepairs) {
  const auto file = scratch_folder() / "stroke.csv";
  write_text(file, kTrace);
  const CliResult result = run_cli("trace info '" + file.string() + "' --repair-gap-ms 5");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("samples    9 over 0.008 s"), std::string::npos) << result.output;  // 7 + 2 filled
  EXPECT_NE(result.output.find("workspace  x 10.0 to 10.8 mm, y -5.2 to -5.0 mm, z 119.5 to 120.0 mm"),
            std::string::npos) << result.output;
  EXPECT_NE(result.output.find("cuts       2 (button 0x1 held): 0.001-0.002 s, 0.007-0.008 s"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("stroke.csv:9: a 3 ms dropout after t = 0.0040 s filled with 2 interpolated samples"),
            std::string::npos) << result.output;
}

TEST(TraceInfo, ABadTraceExitsTwoNamingItsLine) {
  const auto file = scratch_folder() / "stroke.csv";
  write_text(file, kTrace);
  const CliResult gap = run_cli("trace info '" + file.string() + "'");
  EXPECT_EQ(gap.exit_code, 2) << gap.output;
  EXPECT_NE(gap.output.find("stroke.csv:10:1: t_s: a 3 ms dropout"), std::string::npos) << gap.output;
  const CliResult missing = run_cli("trace info '" + (file.parent_path() / "none.csv").string() + "'");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("cannot read trace file"), std::string::npos) << missing.output;
}

// Issue 13, item 7: a UTF-8 byte-order mark (an editor's) was refused with a misleading header
// message, and a file with CR-only line ends got "no header line" with no line number.
TEST(TraceInfo, AcceptsAByteOrderMarkAndLocatesCarriageReturnsAlone) {
  const auto folder = scratch_folder();
  write_text(folder / "bom.csv", "\xEF\xBB\xBF" + kTrace);
  const CliResult bom = run_cli("trace info '" + (folder / "bom.csv").string() + "' --repair-gap-ms 5");
  EXPECT_EQ(bom.exit_code, 0) << bom.output;
  EXPECT_NE(bom.output.find("samples    9 over 0.008 s"), std::string::npos) << bom.output;

  std::string mac = kTrace;
  for (char& c : mac)
    if (c == '\n') c = '\r';
  write_text(folder / "mac.csv", mac);
  const CliResult cr = run_cli("trace info '" + (folder / "mac.csv").string() + "'");
  EXPECT_EQ(cr.exit_code, 2) << cr.output;
  // "# device: Novint Falcon" is 23 characters: the first CR is at line 1, column 24.
  EXPECT_NE(cr.output.find("mac.csv:1:24: a carriage return (CR) alone ends a line here"), std::string::npos)
      << cr.output;
}

TEST(TraceSynthCommand, WritesATraceThatTraceInfoDescribes) {
  const auto folder = scratch_folder();
  const auto file = folder / "two.csv";
  const CliResult synth =
      run_cli("trace synth --out '" + file.string() + "' --seed 3 --stroke -20,15,-5,15 --stroke 0,0,15,-5");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  // A 0.5 s pause, then per stroke 0.5 + 0.3 + length / (10 mm/s) + 0.3 + 0.5 s: 15 mm, then 15.81 mm.
  EXPECT_EQ(synth.output, "wrote " + file.string() + ": 6782 samples over 6.781 s at 1000 Hz, 2 strokes, seed 3\n");
  EXPECT_FALSE(std::filesystem::exists(file.string() + ".partial"));
  const CliResult info = run_cli("trace info '" + file.string() + "'");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("device     Novint Falcon (synthetic)"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("samples    6782 over 6.781 s"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("cuts       2 (button 0x1 held): 1.000-2.799 s, 4.100-5.980 s"), std::string::npos)
      << info.output;
}

TEST(TraceSynthCommand, OverwritesAFileOnlyWithForce) {
  const auto file = scratch_folder() / "kept.csv";
  write_text(file, "precious\n");
  const CliResult refused = run_cli("trace synth --out '" + file.string() + "'");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("kept.csv: --out: exists already; pass --force to overwrite it"), std::string::npos)
      << refused.output;
  EXPECT_EQ(read_bytes(file), "precious\n");
  const CliResult forced = run_cli("trace synth --out '" + file.string() + "' --force");
  EXPECT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_EQ(read_bytes(file).rfind("# device: Novint Falcon (synthetic)\n", 0), 0u);
}

TEST(TraceSynthCommand, ABadOptionExitsTwoNamingItAndWritesNothing) {
  const auto folder = scratch_folder();
  const std::string out = " --out '" + (folder / "t.csv").string() + "'";
  const std::pair<std::string, std::string> cases[] = {
      {"--depth-mm -1", "--depth-mm: must be 0 mm or more (got -1)"},
      {"--depth-mm deep", "--depth-mm"},
      {"--stroke 1,2,3", "--stroke: expected x0,y0,x1,y1"},
      {"--stroke 0,0,70,0", "--stroke: stroke 1 reaches 70 mm"},
      {"--rate-hz 500", "--rate-hz: must be between 900 and 1100 Hz"},
      {"--tremor-um 1500", "--tremor-um: must be at least 0 and under 1000"},
      {"--hover-mm 60", "--hover-mm: hovering 60 mm above the surface"},
      {"--seed -1", "--seed: must be a whole number, 0 or more"},
  };
  for (const auto& [option, message] : cases) {
    const CliResult result = run_cli("trace synth" + out + " " + option);
    EXPECT_EQ(result.exit_code, 2) << option << ": " << result.output;
    EXPECT_NE(result.output.find(message), std::string::npos) << option << ": " << result.output;
    EXPECT_TRUE(std::filesystem::is_empty(folder)) << option << " left a file behind";
  }
}

}  // namespace
}  // namespace bleedsim::test
