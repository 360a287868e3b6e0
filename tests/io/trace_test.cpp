// Falcon traces (core/io/trace_csv.cpp): a valid trace reads back exactly, every kind of bad trace is
// refused with a message that names the file, the physical line and the key (docs/traces.md,
// "Errors"), and a short dropout is repaired by interpolation only when the options allow it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/runtime/input_error.h"
#include "core/io/trace_csv.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

const std::string kPath = "traces/stroke.csv";

// A valid trace, one item per line, so that a test can break line N and expect N in the message.
const std::string kBase =
    "# device: Novint Falcon (bench rig 2)\n"     //  1
    "# frame: libnifalcon\n"                      //  2
    "# rate_hz: 1000\n"                           //  3
    "# origin: synthetic\n"                       //  4
    "t_s,x_m,y_m,z_m,buttons\n"                   //  5
    "0.000,0.0100,-0.0050,0.1200,0\n"             //  6
    "0.001,0.0102,-0.0049,0.1195,1\n"             //  7
    "0.002,0.0104,-0.0048,0.1190,1\n"             //  8
    "0.003,0.0106,-0.0047,0.1185,9\n"             //  9
    "0.004,0.0108,-0.0046,0.1180,0\n";            // 10

// The same motion with the force that was sent.
const std::string kForce =
    "# device: Novint Falcon\n"                            // 1
    "# frame: libnifalcon\n"                               // 2
    "# rate_hz: 1000\n"                                    // 3
    "t_s,x_m,y_m,z_m,buttons,fx_N,fy_N,fz_N\n"             // 4
    "0.000,0.0100,-0.0050,0.1200,0,0,0,0\n"                // 5
    "0.001,0.0102,-0.0049,0.1195,1,0.25,-1.5e-1,2.0\n"     // 6
    "0.002,0.0104,-0.0048,0.1190,1,-3,4,0\n";              // 7

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// `text` with its line `line` (from 1) replaced by `by`.
std::string with_line(const std::string& text, int line, const std::string& by) {
  std::vector<std::string> lines = lines_of(text);
  lines.at(std::size_t(line - 1)) = by;
  std::string result;
  for (const std::string& l : lines) result += l + "\n";
  return result;
}

// Parses `text` as kPath and checks it is refused at `line` (0: the file as a whole), `column`
// (-1: any) and `key`, with a message containing every one of `gists`.
::testing::AssertionResult refused_at(const std::string& text, int line, const std::string& key,
                                      const std::vector<std::string>& gists, int column = -1,
                                      const TraceOptions& options = {}) {
  try {
    parse_trace(text, kPath, options);
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string place = line > 0 ? kPath + ":" + std::to_string(line) + ":" : kPath + ": ";
    bool ok = what.rfind(place, 0) == 0 && e.where().file == kPath && e.where().line == line &&
              (column < 0 || e.where().column == column) && e.key() == key &&
              (key.empty() || what.find(" " + key + ": ") != std::string::npos);
    for (const std::string& gist : gists) ok = ok && what.find(gist) != std::string::npos;
    if (ok) return ::testing::AssertionSuccess();
    ::testing::AssertionResult failure = ::testing::AssertionFailure();
    failure << "expected '" << place << "', column " << column << ", key '" << key << "' and";
    for (const std::string& gist : gists) failure << " '" << gist << "'";
    return failure << "; got line " << e.where().line << " column " << e.where().column << " key '" << e.key()
                   << "': " << what;
  }
  return ::testing::AssertionFailure() << "parsed without an error";
}

TEST(TraceParse, ReadsAValidTraceBackExactly) {
  const Trace t = parse_trace(kBase, kPath);
  EXPECT_EQ(t.path, kPath);
  EXPECT_EQ(t.rate_hz, 1000.0);
  EXPECT_FALSE(t.has_force);
  EXPECT_TRUE(t.repairs.empty());
  ASSERT_EQ(t.samples.size(), 5u);
  EXPECT_EQ(t.samples[0].t_s, 0.0);
  EXPECT_EQ(t.samples[1].t_s, 0.001);
  EXPECT_EQ(t.samples[4].t_s, 0.004);
  EXPECT_EQ(t.samples[1].x_m, 0.0102);
  EXPECT_EQ(t.samples[1].y_m, -0.0049);
  EXPECT_EQ(t.samples[1].z_m, 0.1195);
  EXPECT_EQ(t.samples[3].x_m, 0.0106);
  EXPECT_EQ(t.samples[4].z_m, 0.1180);
  const int buttons[] = {0, 1, 1, 9, 0};
  for (int k = 0; k < 5; ++k) EXPECT_EQ(t.samples[k].buttons, buttons[k]) << "sample " << k;
  for (const TraceSample& s : t.samples) EXPECT_EQ(s.fx_N + s.fy_N + s.fz_N, 0.0);
}

TEST(TraceParse, ReadsTheForceColumns) {
  const Trace t = parse_trace(kForce, kPath);
  EXPECT_TRUE(t.has_force);
  ASSERT_EQ(t.samples.size(), 3u);
  EXPECT_EQ(t.samples[1].fx_N, 0.25);
  EXPECT_EQ(t.samples[1].fy_N, -0.15);
  EXPECT_EQ(t.samples[1].fz_N, 2.0);
  EXPECT_EQ(t.samples[2].fx_N, -3.0);
  EXPECT_EQ(t.samples[2].fy_N, 4.0);
  EXPECT_EQ(t.samples[2].x_m, 0.0104);
  EXPECT_EQ(t.samples[2].buttons, 1);
}

TEST(TraceParse, KeepsMetadataAndSkipsCommentsAndBlankLinesAfterTheHeader) {
  const std::string text = "# device: Novint Falcon (bench rig 2)\n"
                           "# frame: libnifalcon\n"
                           "# rate_hz: 1000\n"
                           "# recorded: 2024-05-01T10:22:03Z\n"
                           "# seed: 42\n"
                           "# operator:  Dr. K  \n"
                           "# a plain comment without a key\n"
                           "t_s,x_m,y_m,z_m,buttons\r\n"
                           "0.000,0.0100,-0.0050,0.1200,0\r\n"
                           "\n"
                           "# stroke starts: this is not metadata\n"
                           "0.001, 0.0102 ,-0.0049,0.1195,1\n";
  const Trace t = parse_trace(text, kPath);
  EXPECT_EQ(t.metadata.at("device"), "Novint Falcon (bench rig 2)");
  EXPECT_EQ(t.metadata.at("frame"), "libnifalcon");
  EXPECT_EQ(t.metadata.at("rate_hz"), "1000");
  EXPECT_EQ(t.metadata.at("recorded"), "2024-05-01T10:22:03Z");
  EXPECT_EQ(t.metadata.at("seed"), "42");
  EXPECT_EQ(t.metadata.at("operator"), "Dr. K");
  EXPECT_EQ(t.metadata.size(), 6u);
  ASSERT_EQ(t.samples.size(), 2u);
  EXPECT_EQ(t.samples[1].x_m, 0.0102);
}

TEST(TraceParse, LoadsAFileAndRefusesAMissingOne) {
  const fs::path dir = fs::temp_directory_path() / ("bleedsim-trace-test-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string file = (dir / "t.csv").string();
  std::ofstream(file) << kBase;
  const Trace t = load_trace(InputFile{file, "trace file"});
  EXPECT_EQ(t.path, file);
  EXPECT_EQ(t.samples.size(), 5u);
  EXPECT_EQ(t.metadata.at("origin"), "synthetic");
  const std::string missing = (dir / "nope.csv").string();
  try {
    load_trace(InputFile{missing, "trace file"});
    ADD_FAILURE() << "a missing file was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, missing);
    EXPECT_EQ(e.where().line, 0);
    EXPECT_NE(std::string(e.what()).find("cannot read trace file"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_trace(InputFile{dir.string(), "trace file"}), InputError);
  fs::remove_all(dir);
}

TEST(TraceBadInput, EmptyFile) {
  EXPECT_TRUE(refused_at("", 0, "", {"the file is empty"}));
  EXPECT_TRUE(refused_at("\n  \n", 0, "", {"the file is empty"}));
}

TEST(TraceBadInput, NoHeaderOrNoSamples) {
  EXPECT_TRUE(refused_at("# device: x\n# frame: libnifalcon\n", 0, "header", {"no header line"}));
  EXPECT_TRUE(refused_at(kBase.substr(0, kBase.find("0.000")) + "# nothing yet\n", 5, "samples",
                         {"no samples after the header"}));
}

TEST(TraceBadInput, MissingRequiredMetadataIsPlacedAtTheHeader) {
  EXPECT_TRUE(refused_at(with_line(kBase, 1, "# made by: hand"), 5, "metadata.device", {"missing (required)"}));
  EXPECT_TRUE(refused_at(with_line(kBase, 2, ""), 5, "metadata.frame", {"missing (required)", "# frame:"}));
  EXPECT_TRUE(refused_at(with_line(kBase, 3, "# rate: 1000"), 5, "metadata.rate_hz",
                         {"missing (required)", "line 3 has 'rate'", "did you mean 'rate_hz'"}));
}

TEST(TraceBadInput, MetadataGivenTwice) {
  EXPECT_TRUE(refused_at(with_line(kBase, 4, "# frame: libnifalcon"), 4, "metadata.frame", {"first on line 2"}));
}

TEST(TraceBadInput, FrameOtherThanLibnifalcon) {
  EXPECT_TRUE(refused_at(with_line(kBase, 2, "# frame: chai3d"), 2, "metadata.frame",
                         {"must be libnifalcon", "(got 'chai3d')"}, 10));
}

TEST(TraceBadInput, RateFarFromOneKilohertz) {
  EXPECT_TRUE(refused_at(with_line(kBase, 3, "# rate_hz: 500"), 3, "metadata.rate_hz",
                         {"must be between 900 and 1100 (got 500)", "near the Falcon's 1 kHz"}, 12));
  EXPECT_TRUE(refused_at(with_line(kBase, 3, "# rate_hz: fast"), 3, "metadata.rate_hz", {"expected a number"}));
}

TEST(TraceBadInput, SamplesSpacedAtAnotherRateThanTheHeaderStates) {
  // rate_hz says 1100 but the samples are 1 ms apart: 10 % off is still allowed, this is 9 %.
  EXPECT_NO_THROW(parse_trace(with_line(kBase, 3, "# rate_hz: 1090"), kPath));
  std::string text = with_line(kBase, 3, "# rate_hz: 900");
  // Samples 1.25 ms apart (800 Hz) against a stated 900 Hz: 11 % off.
  for (int k = 0; k < 5; ++k) {
    std::string line = lines_of(kBase)[std::size_t(5 + k)];
    text = with_line(text, 6 + k, std::to_string(k * 0.00125) + line.substr(line.find(',')));
  }
  EXPECT_TRUE(refused_at(text, 3, "metadata.rate_hz", {"the samples are 800 Hz apart", "not the 900 Hz the header states"}));
}

TEST(TraceBadInput, WrongHeader) {
  EXPECT_TRUE(refused_at(with_line(kBase, 5, "time,px,py,pz"), 5, "header",
                         {"expected the header t_s,x_m,y_m,z_m,buttons or t_s,x_m,y_m,z_m,buttons,fx_N,fy_N,fz_N",
                          "(got 'time,px,py,pz')"}, 1));
  EXPECT_TRUE(refused_at(with_line(kBase, 5, "t_s,x_m,y_m,z_m,buttons,fx_N"), 5, "header", {"(got 't_s,x_m,y_m,z_m,buttons,fx_N')"}));
  // No header at all: the first sample is taken for it.
  EXPECT_TRUE(refused_at(with_line(kBase, 5, "# t_s,x_m,y_m,z_m,buttons"), 6, "header", {"(got '0.000,"}));
}

TEST(TraceBadInput, WrongUnitsInTheHeader) {
  EXPECT_TRUE(refused_at(with_line(kBase, 5, "t_s,x_mm,y_mm,z_mm,buttons"), 5, "header",
                         {"column 2 is 'x_mm'", "positions are in metres (x_m)"}, 5));
  EXPECT_TRUE(refused_at(with_line(kBase, 5, "t_ms,x_m,y_m,z_m,buttons"), 5, "header", {"time is in seconds (t_s)"}, 1));
  EXPECT_TRUE(refused_at(with_line(kForce, 4, "t_s,x_m,y_m,z_m,buttons,fx_lbf,fy_N,fz_N"), 4, "header",
                         {"forces are in newtons (fx_N)"}, 25));
}

TEST(TraceBadInput, WrongNumberOfValuesOnALine) {
  EXPECT_TRUE(refused_at(with_line(kBase, 8, "0.002,0.0104,-0.0048,0.1190"), 8, "columns", {"expected 5 values", "got 4"}));
  EXPECT_TRUE(refused_at(with_line(kForce, 6, "0.001,0.0102,-0.0049,0.1195,1"), 6, "columns", {"expected 8 values", "got 5"}));
}

TEST(TraceBadInput, ValueThatIsNotANumber) {
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,0.0102,abc,0.1195,1"), 7, "y_m", {"expected a number, got 'abc'"}, 14));
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,,-0.0049,0.1195,1"), 7, "x_m", {"got an empty value"}, 7));
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,0x1p-6,-0.0049,0.1195,1"), 7, "x_m", {"expected a number"}));
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,1.0.2,-0.0049,0.1195,1"), 7, "x_m", {"expected a number"}));
}

TEST(TraceBadInput, NanOrInfinity) {
  EXPECT_TRUE(refused_at(with_line(kBase, 8, "0.002,nan,-0.0048,0.1190,1"), 8, "x_m", {"must be a finite number (got nan)"}, 7));
  EXPECT_TRUE(refused_at(with_line(kBase, 8, "0.002,0.0104,-0.0048,-Inf,1"), 8, "z_m", {"must be a finite number (got -Inf)"}));
  EXPECT_TRUE(refused_at(with_line(kBase, 8, "1e999,0.0104,-0.0048,0.1190,1"), 8, "t_s", {"must be a finite number"}));
  EXPECT_TRUE(refused_at(with_line(kForce, 7, "0.002,0.0104,-0.0048,0.1190,1,0,NaN,0"), 7, "fy_N", {"(got NaN)"}));
}

TEST(TraceBadInput, TimeThatIsNotStrictlyIncreasing) {
  EXPECT_TRUE(refused_at(with_line(kBase, 9, "0.002,0.0106,-0.0047,0.1185,9"), 9, "t_s",
                         {"strictly increasing", "0.002 s is not after 0.002 s on line 8"}, 1));
  EXPECT_TRUE(refused_at(with_line(kBase, 9, "0.0005,0.0106,-0.0047,0.1185,9"), 9, "t_s",
                         {"0.0005 s is not after 0.002 s on line 8"}));
}

TEST(TraceBadInput, PositionOutsideTheWorkspace) {
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,0.0612,-0.0049,0.1195,1"), 7, "x_m",
                         {"0.0612 m is outside the Falcon's workspace", "between -0.06 and 0.06 m (-60 to 60 mm)"}, 7));
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,0.0102,-0.0601,0.1195,1"), 7, "y_m", {"outside the Falcon's workspace"}));
  // z is 70 mm: in millimetres (120 for 0.120 m) it would be far outside too.
  EXPECT_TRUE(refused_at(with_line(kBase, 10, "0.004,0.0108,-0.0046,0.070,0"), 10, "z_m",
                         {"0.07 m is outside the Falcon's workspace", "between 0.075 and 0.175 m (75 to 175 mm)"}));
  EXPECT_TRUE(refused_at(with_line(kBase, 6, "0.000,10,-5,120,0"), 6, "x_m", {"10 m is outside"}));
  // The bounds themselves are inside.
  EXPECT_NO_THROW(parse_trace(with_line(kBase, 7, "0.001,-0.060,0.060,0.175,1"), kPath));
  EXPECT_NO_THROW(parse_trace(with_line(kBase, 7, "0.001,0.060,-0.060,0.075,1"), kPath));
}

TEST(TraceBadInput, ButtonsThatAreNotAFourBitMask) {
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,0.0102,-0.0049,0.1195,16"), 7, "buttons",
                         {"must be an integer between 0 and 15", "(got 16)"}, 29));
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,0.0102,-0.0049,0.1195,1.5"), 7, "buttons", {"(got 1.5)"}));
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,0.0102,-0.0049,0.1195,-1"), 7, "buttons", {"(got -1)"}));
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "0.001,0.0102,-0.0049,0.1195,on"), 7, "buttons", {"expected an integer, got 'on'"}));
}

TEST(TraceBadInput, ForceOverTheFalconsMaximum) {
  // (6, 6, 2) N has magnitude 8.72 N: allowed; (6, 6, 3) N has 9 N: refused.
  EXPECT_NO_THROW(parse_trace(with_line(kForce, 7, "0.002,0.0104,-0.0048,0.1190,1,6,6,2"), kPath));
  EXPECT_TRUE(refused_at(with_line(kForce, 7, "0.002,0.0104,-0.0048,0.1190,1,6,6,3"), 7, "force",
                         {"magnitude 9 N", "over the Falcon's 8.9 N maximum"}, 31));
}

// kBase with a 4 ms dropout: the samples at 3, 4 and 5 ms are missing.
const std::string kGap =
    "# device: Novint Falcon\n"                    //  1
    "# frame: libnifalcon\n"                       //  2
    "# rate_hz: 1000\n"                            //  3
    "t_s,x_m,y_m,z_m,buttons,fx_N,fy_N,fz_N\n"     //  4
    "0.000,0.0080,0.0000,0.1000,0,0,0,0\n"         //  5
    "0.001,0.0090,0.0000,0.1000,1,0,0,0\n"         //  6
    "0.002,0.0100,0.0000,0.1000,1,0,0,0\n"         //  7
    "0.006,0.0140,-0.0020,0.1080,0,4,-2,0.8\n"     //  8
    "0.007,0.0150,-0.0020,0.1080,0,4,-2,0.8\n"     //  9
    "0.008,0.0160,-0.0020,0.1080,0,4,-2,0.8\n";    // 10

TEST(TraceBadInput, GapIsRefusedNamingBothLines) {
  EXPECT_TRUE(refused_at(kGap, 8, "t_s", {"a 4 ms dropout after t = 0.0020 s", "between line 7 and line 8"}));
  // A repair limit shorter than the gap does not repair it, and says what the limit is.
  TraceOptions options;
  options.max_repair_gap_s = 0.003;
  EXPECT_TRUE(refused_at(kGap, 8, "t_s", {"between line 7 and line 8", "repairs are allowed up to 3 ms"}, -1, options));
  // 1.5 intervals is still no gap.
  EXPECT_NO_THROW(parse_trace(with_line(kBase, 10, "0.0044,0.0108,-0.0046,0.1180,0"), kPath));
}

TEST(TraceRepair, FillsAGapByLinearInterpolationAndReportsIt) {
  TraceOptions options;
  options.max_repair_gap_s = 0.004;
  const Trace t = parse_trace(kGap, kPath, options);
  ASSERT_EQ(t.samples.size(), 9u);
  ASSERT_EQ(t.repairs.size(), 1u);
  EXPECT_EQ(t.repairs[0], kPath + ":7: a 4 ms dropout after t = 0.0020 s filled with 3 interpolated samples");
  // Hand-computed: a quarter, half and three quarters of the way from line 7 to line 8.
  const double t_s[] = {0.003, 0.004, 0.005};
  const double x_m[] = {0.011, 0.012, 0.013};
  const double y_m[] = {-0.0005, -0.0010, -0.0015};
  const double z_m[] = {0.102, 0.104, 0.106};
  const double fx_N[] = {1, 2, 3};
  const double fy_N[] = {-0.5, -1.0, -1.5};
  const double fz_N[] = {0.2, 0.4, 0.6};
  for (int k = 0; k < 3; ++k) {
    const TraceSample& s = t.samples[std::size_t(3 + k)];
    SCOPED_TRACE("filled sample " + std::to_string(k));
    EXPECT_NEAR(s.t_s, t_s[k], 1e-15);
    EXPECT_NEAR(s.x_m, x_m[k], 1e-15);
    EXPECT_NEAR(s.y_m, y_m[k], 1e-15);
    EXPECT_NEAR(s.z_m, z_m[k], 1e-15);
    EXPECT_NEAR(s.fx_N, fx_N[k], 1e-12);
    EXPECT_NEAR(s.fy_N, fy_N[k], 1e-12);
    EXPECT_NEAR(s.fz_N, fz_N[k], 1e-12);
    EXPECT_EQ(s.buttons, 1) << "held from the sample before the gap";
  }
  // The samples around the gap are untouched.
  EXPECT_EQ(t.samples[2].x_m, 0.0100);
  EXPECT_EQ(t.samples[6].x_m, 0.0140);
  EXPECT_EQ(t.samples[6].buttons, 0);
  for (std::size_t k = 1; k < t.samples.size(); ++k) EXPECT_NEAR(t.samples[k].t_s - t.samples[k - 1].t_s, 0.001, 1e-12);
}


// ---- Encodings (issue 13, item 7) --------------------------------------------------------------

std::vector<double> times_of(const Trace& trace) {
  std::vector<double> t;
  for (const TraceSample& s : trace.samples) t.push_back(s.t_s);
  return t;
}

TEST(TraceEncoding, AUtf8ByteOrderMarkIsSkipped) {
  const Trace t = parse_trace("\xEF\xBB\xBF" + kBase, kPath);
  EXPECT_EQ(t.metadata.at("device"), "Novint Falcon (bench rig 2)");
  EXPECT_EQ(times_of(t), times_of(parse_trace(kBase, kPath)));
  // Columns on the first line count from after the mark, as an editor shows them.
  EXPECT_TRUE(refused_at("\xEF\xBB\xBF" + with_line(kBase, 1, "# frame: chai3d"), 1, "metadata.frame", {"chai3d"},
                         10));
}

TEST(TraceEncoding, AUtf16ByteOrderMarkIsRefusedSayingSo) {
  EXPECT_TRUE(refused_at("\xFF\xFE#\0 \0d\0", 1, "", {"UTF-16 byte-order mark", "UTF-8"}, 1));
}

TEST(TraceEncoding, CarriageReturnsAloneAreLocatedAtTheFirst) {
  std::string cr = kBase;
  std::replace(cr.begin(), cr.end(), '\n', '\r');
  // The first line is "# device: Novint Falcon (bench rig 2)", 37 characters: its CR is column 38.
  EXPECT_TRUE(refused_at(cr, 1, "", {"carriage return (CR) alone ends a line", "LF or CR LF"}, 38));
  // One in the middle of a file of LF lines is found on its own line.
  EXPECT_TRUE(refused_at(with_line(kBase, 8, "0.002,0.0104,\r-0.0048,0.1190,1"), 8, "", {"carriage return"}, 14));
  // CR LF is a line end like LF.
  std::string crlf;
  for (const std::string& line : lines_of(kBase)) crlf += line + "\r\n";
  EXPECT_EQ(times_of(parse_trace(crlf, kPath)), times_of(parse_trace(kBase, kPath)));
}

// ---- Memory (issue 13, item 5; issue 38, item 13) ---------------------------------------------

// kBase's header, then `count` samples 1 ms apart from t = 0, one line each.
std::string long_trace(int count, const std::string& header = kBase.substr(0, kBase.find("0.000,"))) {
  std::string text = header;
  char line[64];
  for (int n = 0; n < count; ++n) {
    std::snprintf(line, sizeof line, "%d.%03d,0.0100,-0.0050,0.1200,0\n", n / 1000, n % 1000);
    text += line;
  }
  return text;
}

TEST(TraceMemory, TheStoreOfSamplesIsCountedBeforeItGrows) {
  // The store grows from 1024 samples of 64 bytes: 2000 samples need it grown to 2048, beside the
  // 1024 held.
  const std::string text = long_trace(2000);
  TraceOptions options;
  options.memory_room = 150000;
  EXPECT_TRUE(refused_at(text, 0, "", {"cannot read trace file: keeping its samples up to t = 1.0240 s, 1025 of them, "
                                       "needs 192.00 KiB of host memory, but only 146.48 KiB is available"},
                         -1, options));
  options.memory_room = 3072 * 64;
  EXPECT_EQ(parse_trace(text, kPath, options).samples.size(), 2000u);
}

TEST(TraceMemory, RepairsAreCountedBeforeTheyAreKept) {
  // A 2.9 s dropout is repaired into 2899 samples: past the first 1024 the store must grow.
  const std::string far = with_line(with_line(with_line(kGap, 8, "2.902,0.0140,-0.0020,0.1080,0,4,-2,0.8"), 9,
                                               "2.903,0.0150,-0.0020,0.1080,0,4,-2,0.8"),
                                     10, "2.904,0.0160,-0.0020,0.1080,0,4,-2,0.8");
  TraceOptions options;
  options.max_repair_gap_s = 3.0;
  options.memory_room = 100000;  // 1024 samples' store, not a grown one beside it
  EXPECT_TRUE(refused_at(far, 0, "", {"keeping its samples up to t = 1.0240 s, 1025 of them", "but only"}, -1, options));
  options.memory_room.reset();
  EXPECT_EQ(parse_trace(far, kPath, options).samples.size(), 2905u);
}

TEST(TraceStream, KeepsTheSamplesUpToTheFirstPastKeepAndReadsNoFurther) {
  // 5 s of samples, then a line that is no sample: a run of 0.2 s keeps 202 (0 to 0.201 s) and
  // never meets it; reading the whole file does.
  const std::string text = long_trace(5000) + "not,a,sample\n";
  TraceOptions options;
  options.keep_s = 0.2;
  const Trace t = parse_trace(text, kPath, options);
  ASSERT_EQ(t.samples.size(), 202u);
  EXPECT_EQ(t.samples.back().t_s, 0.201);
  EXPECT_LE(t.samples.capacity(), 1024u);
  EXPECT_TRUE(refused_at(text, 5006, "columns", {"expected 5 values"}));
}

TEST(TraceStream, ReadTraceHandsOnEverySampleAndKeepsNone) {
  const fs::path dir = fs::temp_directory_path() / ("bleedsim-trace-stream-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string file = (dir / "t.csv").string();
  std::ofstream(file) << long_trace(30000);
  std::size_t seen = 0;
  const Trace t = read_trace(InputFile{file, "trace file"}, {}, [&seen](const TraceSample& s) {
    EXPECT_EQ(s.buttons, 0);
    return ++seen > 0;
  });
  EXPECT_EQ(seen, 30000u);
  EXPECT_TRUE(t.samples.empty());
  EXPECT_NEAR(t.median_interval_s, 0.001, 1e-12) << "of the first " << kTraceRateWindow << " intervals";
  fs::remove_all(dir);
}

TEST(TraceStream, TheRateIsCheckedBeforeADropoutInItsWindow) {
  // Samples 2 ms apart, stated as 1000 Hz: every interval is a dropout, but the rate explains them.
  std::string text = kBase.substr(0, kBase.find("0.000,"));
  for (int n = 0; n < 20; ++n) text += "0.0" + std::to_string(10 + 2 * n) + ",0.0100,-0.0050,0.1200,0\n";
  EXPECT_TRUE(refused_at(text, 3, "metadata.rate_hz", {"the samples are 500 Hz apart (median interval 2 ms)"}));
  // Past the window a dropout is refused where it is.
  const std::string late = long_trace(int(kTraceRateWindow) + 10) + "15.000,0.0100,-0.0050,0.1200,0\n";
  EXPECT_TRUE(refused_at(late, int(kTraceRateWindow) + 16, "t_s", {"dropout after t = 10.0090 s"}));
}

TEST(TraceStream, ALineLongerThanTheCapIsRefusedAtIt) {
  const std::string text = with_line(kBase, 4, "# origin: " + std::string(kTraceMaxLineBytes, 'x'));
  EXPECT_TRUE(refused_at(text, 4, "", {"the line is longer than 4096 characters"}));
  // A line of exactly the cap is read.
  EXPECT_NO_THROW(parse_trace(with_line(kBase, 4, "# origin: " + std::string(kTraceMaxLineBytes - 10, 'x')), kPath));
}

}  // namespace
}  // namespace bleedsim
