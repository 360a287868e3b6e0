#pragma once
// Synthetic Novint Falcon traces (docs/traces.md, "bleedsim trace synth"): a surgeon's cutting
// strokes as the stylus would record them, with a physiological hand tremor on top, written in the
// trace format that core/io/trace_csv.h reads. The same spec always gives the same bytes.
#include <cstdint>
#include <string>
#include <vector>

namespace bleedsim {

// One stroke, in libnifalcon's device frame (x right, y up), millimetres, with the grip buttons held
// along it: 1 (the first) cuts; 2 (the second) is the suction's default.
struct StrokeSpec {
  double from_x_mm = 0, from_y_mm = 0, to_x_mm = 0, to_y_mm = 0;
  int buttons = 1;
};

// Every field is named in messages by its `bleedsim trace synth` option (in brackets).
struct SynthSpec {
  std::uint64_t seed = 1;                          // [--seed] draws the tremor
  std::vector<StrokeSpec> strokes{{-10, 0, 10, 0}};  // [--stroke] the strokes, in order
  double surface_z_mm = 120.0;  // [--surface-z-mm] device z of the tissue surface; the tool is in it below this
  double depth_mm = 2.0;        // [--depth-mm] how far below the surface a stroke cuts
  double hover_mm = 15.0;       // [--hover-mm] how far above the surface the tool waits between strokes
  double speed_mm_s = 10.0;     // [--speed-mm-s] along a stroke
  double approach_s = 0.5;      // [--approach-s] from hover down to the surface
  double press_s = 0.3;         // [--press-s] from the surface down to depth, the button already held
  double lift_s = 0.3;          // [--lift-s] from depth back up to hover, the button released
  double pause_s = 0.5;         // [--pause-s] above the tissue before, between and after the strokes
  double tremor_um = 100.0;     // [--tremor-um] peak tremor per axis, under a millimetre; 0 for none
  double rate_hz = 1000.0;      // [--rate-hz] samples per second
};

// The trace as CSV text, metadata included: t_s,x_m,y_m,z_m,buttons, sample i at t = i / rate_hz.
// Throws InputError, its key the option at fault, when the spec is out of range or would take the
// tool outside the Falcon's workspace.
std::string synthesize_trace(const SynthSpec& spec);

}  // namespace bleedsim
