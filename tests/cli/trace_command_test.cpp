// bleedsim trace info, as a user runs it: a good trace described, a bad one refused with its line.
#include <gtest/gtest.h>

#include <string>

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

}  // namespace
}  // namespace bleedsim::test
