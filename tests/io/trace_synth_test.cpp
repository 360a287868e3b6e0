// Synthetic Falcon traces (core/io/trace_synth.cpp): the bytes follow from the seed, the trace reads
// back through the loader, the button is held exactly while the tool presses in and cuts, the cut
// runs at depth between the stroke's ends, the tremor is sub-millimetre and 8–12 Hz, and a spec that
// would leave the Falcon's workspace is refused naming the option.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "core/runtime/input_error.h"
#include "core/io/trace_csv.h"
#include "core/io/trace_synth.h"

namespace bleedsim {
namespace {

// 1 µm, the resolution the file is written at, as the tolerance on top of any expected value.
constexpr double kWritten_m = 0.5e-6 + 1e-12;

Trace synth(const SynthSpec& spec) { return parse_trace(synthesize_trace(spec), "synth.csv"); }

// Button-0x1 stretches as sample indices [begin, end).
struct Stretch {
  std::size_t begin, end;
};

std::vector<Stretch> held(const Trace& trace) {
  std::vector<Stretch> found;
  for (std::size_t i = 0; i < trace.samples.size(); ++i) {
    if (!(trace.samples[i].buttons & 0x1)) continue;
    if (found.empty() || found.back().end != i) found.push_back({i, i});
    found.back().end = i + 1;
  }
  return found;
}

SynthSpec three_strokes() {
  SynthSpec spec;
  spec.seed = 2;
  spec.pause_s = 0.6;
  spec.strokes = {{-20, 15, -5, 15}, {0, 0, 15, -5}, {-15, -15, 5, -20}};
  return spec;
}

TEST(TraceSynth, TheSameSeedGivesTheSameBytesAndTheSeedDrawsOnlyTheTremor) {
  SynthSpec spec;
  const std::string text = synthesize_trace(spec);
  EXPECT_EQ(synthesize_trace(spec), text);

  SynthSpec other = spec;
  other.seed = 2;
  const Trace a = synth(spec), b = synth(other);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_EQ(a.samples[i].buttons, b.samples[i].buttons) << "sample " << i;
    moved += a.samples[i].x_m != b.samples[i].x_m;
  }
  EXPECT_GT(moved, a.samples.size() / 2) << "another seed should shake the tool differently";

  spec.tremor_um = other.tremor_um = 0;
  const Trace still_a = synth(spec), still_b = synth(other);
  for (std::size_t i = 0; i < still_a.samples.size(); ++i) {
    EXPECT_EQ(still_a.samples[i].x_m, still_b.samples[i].x_m) << "sample " << i;
    EXPECT_EQ(still_a.samples[i].z_m, still_b.samples[i].z_m) << "sample " << i;
  }
}

TEST(TraceSynth, ReadsBackAtTheRateWithMetadataThatRegeneratesIt) {
  SynthSpec spec;
  spec.rate_hz = 1100;
  const Trace t = synth(spec);
  EXPECT_EQ(t.rate_hz, 1100.0);
  EXPECT_FALSE(t.has_force);
  EXPECT_TRUE(t.repairs.empty());
  EXPECT_EQ(t.metadata.at("device"), "Novint Falcon (synthetic)");
  EXPECT_EQ(t.metadata.at("frame"), "libnifalcon");
  EXPECT_EQ(t.metadata.at("origin"), "synthetic");
  EXPECT_EQ(t.metadata.at("seed"), "1");
  EXPECT_EQ(t.metadata.at("generator"),
            "bleedsim trace synth --seed 1 --stroke -10,0,10,0 --surface-z-mm 120 --depth-mm 2 --hover-mm 15 "
            "--speed-mm-s 10 --approach-s 0.5 --press-s 0.3 --lift-s 0.3 --pause-s 0.5 --tremor-um 100 "
            "--rate-hz 1100");
  // pause, approach, press, the 20 mm stroke at 10 mm/s, lift, pause: 4.1 s, sample i at i / rate.
  ASSERT_EQ(t.samples.size(), std::size_t(std::lround(4.1 * 1100)) + 1);
  for (std::size_t i = 0; i < t.samples.size(); ++i)
    ASSERT_NEAR(t.samples[i].t_s, double(i) / 1100, 0.5e-4 + 1e-12) << "sample " << i;
}

TEST(TraceSynth, TheButtonIsHeldExactlyWhileThePressAndTheStrokeLast) {
  const SynthSpec spec;  // press from 0.5 + 0.5 s, for 0.3 s, then 20 mm at 10 mm/s
  const Trace t = synth(spec);
  const std::vector<Stretch> cuts = held(t);
  ASSERT_EQ(cuts.size(), 1u);
  EXPECT_EQ(cuts[0].begin, 1000u);
  EXPECT_EQ(cuts[0].end, 3300u);
  for (std::size_t i = 0; i < t.samples.size(); ++i)
    EXPECT_EQ(t.samples[i].buttons, i >= 1000 && i < 3300 ? 1 : 0) << "sample " << i;
}

TEST(TraceSynth, TheCutRunsAtDepthFromTheStrokesStartToItsEnd) {
  SynthSpec spec;
  spec.strokes = {{-12, 4, 12, -4}};
  spec.depth_mm = 3;
  const Trace t = synth(spec);
  const double tremor_m = spec.tremor_um * 1e-6, depth_z_m = (spec.surface_z_mm - spec.depth_mm) / 1000;
  const std::vector<Stretch> cuts = held(t);
  ASSERT_EQ(cuts.size(), 1u);
  const std::size_t stroke_begin = cuts[0].begin + std::size_t(spec.press_s * spec.rate_hz);
  for (std::size_t i = stroke_begin; i < cuts[0].end; ++i)
    ASSERT_NEAR(t.samples[i].z_m, depth_z_m, tremor_m + kWritten_m) << "sample " << i;

  const TraceSample& first = t.samples[stroke_begin];
  EXPECT_NEAR(first.x_m, -0.012, tremor_m + kWritten_m);
  EXPECT_NEAR(first.y_m, 0.004, tremor_m + kWritten_m);
  // The last held sample is one tick short of the end: 10 µm at 10 mm/s and 1 kHz.
  const TraceSample& last = t.samples[cuts[0].end - 1];
  const double tick_m = spec.speed_mm_s / spec.rate_hz / 1000;
  EXPECT_NEAR(last.x_m, 0.012, tremor_m + tick_m + kWritten_m);
  EXPECT_NEAR(last.y_m, -0.004, tremor_m + tick_m + kWritten_m);
  // Lifted, the tool comes to rest above the end of the stroke.
  const TraceSample& rest = t.samples.back();
  EXPECT_NEAR(rest.x_m, 0.012, tremor_m + kWritten_m);
  EXPECT_NEAR(rest.z_m, (spec.surface_z_mm + spec.hover_mm) / 1000, tremor_m + kWritten_m);
}

// The strongest frequency of `signal`, sampled at `rate_hz`, between 1 and 50 Hz.
double strongest_hz(const std::vector<double>& signal, double rate_hz) {
  double best_hz = 0, best = -1;
  for (double f = 1; f <= 50; f += 0.25) {
    std::complex<double> sum = 0;
    for (std::size_t i = 0; i < signal.size(); ++i)
      sum += signal[i] * std::polar(1.0, -2 * M_PI * f * double(i) / rate_hz);
    if (std::abs(sum) > best) best = std::abs(sum), best_hz = f;
  }
  return best_hz;
}

TEST(TraceSynth, TheTremorIsSubMillimetreAndPhysiological) {
  SynthSpec spec = three_strokes();
  spec.tremor_um = 250;
  const Trace shaking = synth(spec);
  spec.tremor_um = 0;
  const Trace still = synth(spec);
  ASSERT_EQ(shaking.samples.size(), still.samples.size());
  for (double TraceSample::*axis : {&TraceSample::x_m, &TraceSample::y_m, &TraceSample::z_m}) {
    std::vector<double> tremor;
    for (std::size_t i = 0; i < still.samples.size(); ++i)
      tremor.push_back(shaking.samples[i].*axis - still.samples[i].*axis);
    const double peak = std::max(-*std::min_element(tremor.begin(), tremor.end()),
                                 *std::max_element(tremor.begin(), tremor.end()));
    EXPECT_LE(peak, 250e-6 + 2 * kWritten_m);
    EXPECT_GE(peak, 100e-6) << "three sinusoids over 10 s should come near their summed amplitude";
    const double hz = strongest_hz(tremor, spec.rate_hz);
    EXPECT_GE(hz, 8.0);
    EXPECT_LE(hz, 12.0);
  }
}

TEST(TraceSynth, SeveralStrokesAreSeveralCutsWithTheToolLiftedBetween) {
  const SynthSpec spec = three_strokes();
  const Trace t = synth(spec);
  const std::vector<Stretch> cuts = held(t);
  ASSERT_EQ(cuts.size(), 3u);
  const double tremor_m = spec.tremor_um * 1e-6, hover_z_m = (spec.surface_z_mm + spec.hover_mm) / 1000;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    // lift, pause, approach: 0.3 + 0.6 + 0.5 s between one cut's end and the next's start
    EXPECT_NEAR(double(cuts[k + 1].begin - cuts[k].end), 1400, 1) << "after cut " << k + 1;
    // Out of the tissue from the end of the lift until the next press.
    const std::size_t lifted = cuts[k].end + 300;
    for (std::size_t i = lifted; i < cuts[k + 1].begin; ++i)
      ASSERT_GT(t.samples[i].z_m, spec.surface_z_mm / 1000 - tremor_m - kWritten_m) << "sample " << i;
    // Halfway through the pause the tool is at hover height, halfway to the next stroke.
    const TraceSample& mid = t.samples[lifted + 300];
    EXPECT_NEAR(mid.z_m, hover_z_m, tremor_m + kWritten_m);
    const StrokeSpec& from = spec.strokes[k], &to = spec.strokes[k + 1];
    EXPECT_NEAR(mid.x_m, (from.to_x_mm + to.from_x_mm) / 2000, tremor_m + kWritten_m);
    EXPECT_NEAR(mid.y_m, (from.to_y_mm + to.from_y_mm) / 2000, tremor_m + kWritten_m);
  }
}

// A stroke may hold other buttons than the cutting one (a suction pass holds the second): each
// stroke's press and stroke hold exactly its own buttons, and nothing is held between strokes; the
// generator line names the buttons, so the file makes itself again.
TEST(TraceSynth, EachStrokeHoldsItsOwnButtons) {
  SynthSpec spec = three_strokes();
  spec.strokes[1].buttons = 2;
  spec.strokes[2].buttons = 3;
  const Trace t = synth(spec);
  std::vector<int> held_in_order;
  for (const TraceSample& s : t.samples)
    if (s.buttons != 0 && (held_in_order.empty() || held_in_order.back() != s.buttons)) held_in_order.push_back(s.buttons);
  EXPECT_EQ(held_in_order, (std::vector<int>{1, 2, 3}));
  EXPECT_NE(t.metadata.at("generator").find("--stroke 0,0,15,-5,2 --stroke -15,-15,5,-20,3 --surface"),
            std::string::npos);
}

TEST(TraceSynth, AStrokeAtTheWorkspaceEdgeLessTheTremorIsAccepted) {
  SynthSpec spec;  // values exact in binary, so that the edge is the edge
  spec.tremor_um = 125;
  spec.strokes = {{-59.875, 59.875, 59.875, -59.875}};
  spec.surface_z_mm = 77.125;  // 2 mm deep and the tremor: down to 75 mm
  spec.hover_mm = 97.75;       // and up to 175 mm
  spec.speed_mm_s = 100;
  const Trace t = synth(spec);
  EXPECT_EQ(held(t).size(), 1u);
}

// synthesize_trace(spec changed by `change`) is refused with `key` and a message containing `gist`.
::testing::AssertionResult refused(const std::function<void(SynthSpec&)>& change, const std::string& key,
                                   const std::string& gist) {
  SynthSpec spec;
  change(spec);
  try {
    synthesize_trace(spec);
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (e.key() == key && what.find(gist) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected key '" << key << "' and '" << gist << "'; got key '" << e.key()
                                         << "': " << what;
  }
  return ::testing::AssertionFailure() << "accepted";
}

TEST(TraceSynth, RefusesABadSpecNamingTheOption) {
  EXPECT_TRUE(refused([](SynthSpec& s) { s.rate_hz = 500; }, "--rate-hz", "between 900 and 1100 Hz (got 500)"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.speed_mm_s = 0; }, "--speed-mm-s", "positive number of mm/s (got 0)"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.approach_s = -1; }, "--approach-s", "positive number of seconds"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.press_s = std::nan(""); }, "--press-s", "positive number of seconds"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.lift_s = 0; }, "--lift-s", "positive number of seconds"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.pause_s = 0; }, "--pause-s", "positive number of seconds"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.depth_mm = -0.5; }, "--depth-mm", "must be 0 mm or more (got -0.5)"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.tremor_um = 1000; }, "--tremor-um", "sub-millimetre (got 1000)"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.tremor_um = -1; }, "--tremor-um", "at least 0"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.hover_mm = 0; }, "--hover-mm", "positive number of mm"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.hover_mm = 0.05; }, "--hover-mm", "clear of the tissue"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.hover_mm = 55; }, "--hover-mm", "to z = 175.1 mm, above the Falcon's"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.surface_z_mm = 200; }, "--surface-z-mm",
                      "inside the Falcon's workspace (z 75 to 175 mm) (got 200)"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.surface_z_mm = 76; }, "--depth-mm", "to z = 73.9 mm, below the Falcon's"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.strokes.clear(); }, "--stroke", "at least one stroke"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.strokes.push_back({0, 0, 59.95, 0}); }, "--stroke",
                      "stroke 2 reaches 59.95 mm; with the 0.1 mm tremor"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.strokes[0].from_y_mm = -65; }, "--stroke", "stroke 1 reaches -65 mm"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.strokes.push_back({1, 2, 1, 2}); }, "--stroke",
                      "stroke 2 starts and ends at (1, 2) mm"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.strokes.push_back({1, 2, 3, 4, 16}); }, "--stroke",
                      "stroke 2 holds buttons 16: the grip buttons are a bitmask from 1 to 15"));
  EXPECT_TRUE(refused([](SynthSpec& s) { s.speed_mm_s = 0.01; }, "", "the trace would last 2002 s, over the 600 s"));
}

}  // namespace
}  // namespace bleedsim
