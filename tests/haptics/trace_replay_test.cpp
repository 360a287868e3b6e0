// Replaying a Falcon trace (core/haptics/trace_replay.cpp, Simulation::step): the sample of each tick, the
// [haptics] table of a scenario, and a run whose stylus cuts the tissue where the trace says.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/haptics/trace_replay.h"
#include "core/io/scenario.h"
#include "core/runtime/input_error.h"
#include "core/simulation/frame_hash.h"
#include "core/simulation/simulation.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

Trace trace_of(std::vector<TraceSample> samples) {
  Trace trace;
  trace.rate_hz = 1000;
  trace.samples = std::move(samples);
  return trace;
}

TEST(TraceReplay, InterpolatesBetweenTheRecordedSamples) {
  // A recorder whose clock does not meet the ticks: samples at 0, 1.25 and 2.5 ms.
  const Trace trace = trace_of({{0.0, 0.000, 0.010, 0.120, 1},
                                {0.00125, 0.001, 0.010, 0.119, 0},
                                {0.0025, 0.002, 0.012, 0.118, 1}});
  const DeviceSample s1 = trace_sample_at_tick(trace, 1);  // t = 1 ms: 4/5 of the way to 1.25 ms
  EXPECT_NEAR(s1.position_m.x(), 0.0008, 1e-15);
  EXPECT_NEAR(s1.position_m.z(), 0.1192, 1e-15);
  EXPECT_EQ(s1.buttons, 1);  // as recorded at 0 ms, the sample at or before
  const DeviceSample s2 = trace_sample_at_tick(trace, 2);  // t = 2 ms: 3/5 of the way from 1.25 ms
  EXPECT_NEAR(s2.position_m.y(), 0.0112, 1e-15);
  EXPECT_EQ(s2.buttons, 0);
  const DeviceSample end = trace_sample_at_tick(trace, 3);  // past the end: where it was left
  EXPECT_EQ(end.position_m, Eigen::Vector3d(0.002, 0.012, 0.118));
  EXPECT_EQ(trace_sample_at_tick(trace, 500000).buttons, 1);
}

TEST(TraceReplay, TickZeroIsTheFirstSampleWhereverTheTraceStarts) {
  const Trace trace = trace_of({{12.5, 0.001, 0.002, 0.130, 0}, {12.501, 0.002, 0.002, 0.130, 0}});
  EXPECT_EQ(trace_sample_at_tick(trace, 0).position_m, Eigen::Vector3d(0.001, 0.002, 0.130));
  EXPECT_THROW(trace_sample_at_tick(trace, -1), std::invalid_argument);
  EXPECT_THROW(trace_sample_at_tick(trace_of({}), 0), std::invalid_argument);
}

class ScratchFolder {
 public:
  ScratchFolder() : path_(fs::temp_directory_path() / ("bleedsim-replay-" + std::to_string(getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// 300 ms at 1 kHz: the stylus hovers 5 mm above the surface (z = 120 mm), presses 2 mm in at
// 50 ms with button 0x1 and draws 3 mm to the right until 250 ms, then lifts.
std::string stroke_trace() {
  std::string text = "# device: test\n# frame: libnifalcon\n# rate_hz: 1000\nt_s,x_m,y_m,z_m,buttons\n";
  for (int n = 0; n < 300; ++n) {
    const bool pressed = n >= 50 && n < 250;
    const double x_mm = pressed ? -1.5 + 3.0 * (n - 50) / 200.0 : (n < 50 ? -1.5 : 1.5);
    char line[96];
    std::snprintf(line, sizeof line, "%.3f,%.6f,%.6f,%.6f,%d\n", n / 1000.0, x_mm / 1000, 0.0,
                  (pressed ? 118.0 : 125.0) / 1000, pressed ? 1 : 0);
    text += line;
  }
  return text;
}

// A 16 × 12 mm panel (0.25 mm pixels) with the spread, 0.4 s at 30 Hz, and a stylus whose
// device origin lies over the panel point (8, 6) mm.
std::string stroke_scenario(const std::string& haptic_lines) {
  return "[scene]\nwidth_px = 64\nheight_px = 48\nwidth_mm = 16.0\nheight_mm = 12.0\nduration_s = 0.4\n"
         "[spread]\nradius_mm = 1.0\ngrowth_per_s = 5.0\n"
         "[haptics]\n" + haptic_lines;
}

Scene load_in(const ScratchFolder& scratch, const std::string& scenario) {
  std::ofstream(scratch.path() / "stroke.csv") << stroke_trace();
  fs::create_directories(scratch.path() / "scenes");
  const fs::path file = scratch.path() / "scenes" / "stroke.toml";
  std::ofstream(file) << scenario;
  return load_scenario(file.string()).scene;
}

TEST(HapticsScenario, ReadsTheTableAndTheTraceRelativeToTheScenario) {
  const ScratchFolder scratch;
  const Scene scene = load_in(scratch, stroke_scenario("trace = \"../stroke.csv\"\nstiffness_N_per_m = 800\n"
                                                       "surface_z_mm = 119.5\ncut_spacing_mm = 0.5\n"));
  ASSERT_TRUE(scene.haptics && scene.trace);
  EXPECT_EQ(scene.trace->samples.size(), 300u);
  EXPECT_EQ(scene.haptics->stiffness_N_per_m, 800.0);
  EXPECT_EQ(scene.haptics->surface_z_mm, 119.5);
  EXPECT_EQ(scene.haptics->cut_spacing_mm, 0.5);
  EXPECT_EQ(scene.haptics->origin_x_mm, 8.0);  // the default: the panel's centre
  EXPECT_EQ(scene.haptics->origin_y_mm, 6.0);
  EXPECT_EQ(scene.haptics->damping_Ns_per_m, 0.5);
  EXPECT_EQ(scene.haptics->cut_buttons, 1);
}

// The error load_in's scenario gives, as text; "" when it loads.
std::string refusal(const std::string& haptic_lines) {
  const ScratchFolder scratch;
  try {
    load_in(scratch, stroke_scenario(haptic_lines));
  } catch (const InputError& e) {
    return std::string(e.what()).substr(std::string(e.what()).find("stroke.toml"));
  }
  return "";
}

TEST(HapticsScenario, RefusesWhatCannotBeFeltOrFound) {
  // Lines: [haptics] is line 10, the keys follow it.
  EXPECT_EQ(refusal("stiffness_N_per_m = 800\n"), "stroke.toml:10:1: haptics.trace: missing (required)");
  const std::string missing = refusal("trace = \"../nowhere.csv\"\n");
  EXPECT_EQ(missing.rfind("stroke.toml:11:9: haptics.trace: cannot read trace file '", 0), 0u) << missing;
  EXPECT_NE(missing.find("nowhere.csv': No such file or directory"), std::string::npos) << missing;
  const std::string stiff = refusal("trace = \"../stroke.csv\"\nstiffness_N_per_m = 3000\ndamping_Ns_per_m = 0.2\n");
  EXPECT_EQ(stiff.rfind("stroke.toml:12:21: haptics.stiffness_N_per_m: k·T/2 + |b| = 1.5 + 0.2 = 1.7 N·s/m", 0), 0u)
      << stiff;
  const std::string damped = refusal("trace = \"../stroke.csv\"\ndamping_Ns_per_m = 1.3\n");
  EXPECT_EQ(damped.rfind("stroke.toml:12:20: haptics.damping_Ns_per_m: k·T/2 + |b| = 0.25 + 1.3 = 1.55 N·s/m", 0), 0u)
      << damped;
  EXPECT_EQ(refusal("trace = \"../stroke.csv\"\nmax_force_N = 9\n"),
            "stroke.toml:12:15: haptics.max_force_N: must be greater than 0 and at most 8.9 (got 9)");
  EXPECT_EQ(refusal("trace = \"../stroke.csv\"\ncut_buton = 1\n"),
            "stroke.toml:12:1: haptics.cut_buton: unknown key; did you mean 'cut_button'?");
  EXPECT_EQ(refusal("trace = \"../stroke.csv\"\nsurface_z_mm = 60\n"),
            "stroke.toml:12:16: haptics.surface_z_mm: must be between 75 and 175 (got 60)");
}

TEST(HapticsReplay, TheStylusCutsWhereTheTraceSaysAndTheFramesShowIt) {
  const ScratchFolder scratch;
  Simulation sim(load_in(scratch, stroke_scenario("trace = \"../stroke.csv\"\n")));
  const std::vector<int> ticks_per_frame = {34, 33, 34, 33, 33, 34, 33, 33, 34, 33, 33, 34};  // 401: 0..400 ms
  std::int64_t ticks = 0;
  for (std::size_t k = 0; k < ticks_per_frame.size(); ++k) {
    sim.step();
    ASSERT_EQ(sim.haptic_ticks().size(), std::size_t(ticks_per_frame[k])) << "frame " << k;
    EXPECT_EQ(sim.haptic_ticks().front().tick, ticks);
    ticks += ticks_per_frame[k];
    EXPECT_EQ(sim.haptic_tick_seconds().size(), sim.haptic_ticks().size());
  }
  // 200 ticks (50..249) in contact with the button, 0.015 mm a tick from panel x = 6.5 mm: a cut
  // at once, then one each time the tip has gone 1 mm (67 ticks, 1.005 mm): at ticks 50, 117, 184.
  ASSERT_EQ(sim.cuts().size(), 3u);
  EXPECT_NEAR(sim.cuts()[0].x_mm, 6.5, 1e-9);
  EXPECT_NEAR(sim.cuts()[0].y_mm, 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(sim.cuts()[0].start_s, 0.050);
  EXPECT_NEAR(sim.cuts()[2].x_mm, 6.5 + 2 * 1.005, 1e-9);
  EXPECT_DOUBLE_EQ(sim.cuts()[2].start_s, 0.184);
  // The stain lies along the stroke and nowhere far from it. The pixels nearest the first and the
  // last cut have centres 0.177 and 0.170 mm away: ((1 − d) / 1)⁶ ≈ 0.31 at full amplitude.
  const std::vector<std::uint8_t> bytes = sim.copy_field("spread/stain");
  const float* stain = reinterpret_cast<const float*>(bytes.data());
  EXPECT_GT(stain[24 * 64 + 26], 0.3f);
  EXPECT_GT(stain[24 * 64 + 34], 0.3f);
  EXPECT_EQ(stain[24 * 64 + 5], 0.0f);
  EXPECT_EQ(stain[5 * 64 + 32], 0.0f);
}

TEST(HapticsReplay, TheHapticChannelIsPartOfTheFrameHash) {
  const ScratchFolder scratch;
  const Scene scene = load_in(scratch, stroke_scenario("trace = \"../stroke.csv\"\n"));
  Simulation a(scene), b(scene);
  Scene stiffer = scene;
  stiffer.haptics->stiffness_N_per_m = 600;  // a different force, the same cuts and frames
  Simulation c(stiffer);
  for (int k = 0; k < 3; ++k) a.step(), b.step(), c.step();
  const auto ha = hash_fields(a), hb = hash_fields(b), hc = hash_fields(c);
  ASSERT_EQ(ha.back().first, "haptics");
  EXPECT_EQ(ha, hb);
  EXPECT_EQ(ha.front(), hc.front());     // the frames agree
  EXPECT_NE(ha.back().second, hc.back().second);  // the forces do not
}

}  // namespace
}  // namespace bleedsim