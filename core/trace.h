#pragma once
// Recorded Novint Falcon stylus traces (docs/traces.md): a CSV with a metadata block, a header
// with explicit units and one sample per line, read and validated here. Every problem is an
// InputError that names the file, the line and the key; a short dropout may instead be repaired
// (TraceOptions::max_repair_gap_s), and each repair is described in Trace::repairs.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/input_error.h"

namespace bleedsim {

// One tick of the device, in libnifalcon's frame and units: seconds, metres, newtons.
struct TraceSample {
  double t_s = 0;
  double x_m = 0, y_m = 0, z_m = 0;
  std::uint8_t buttons = 0;  // bitmask of the four grip buttons, 0x1..0x8
  double fx_N = 0, fy_N = 0, fz_N = 0;  // the force that was sent; 0 when the trace has none
};

struct Trace {
  std::string path;
  std::map<std::string, std::string> metadata;  // every `# key: value` line, values as text
  double rate_hz = 0;                            // metadata rate_hz, checked against the samples
  bool has_force = false;                        // the header has fx_N,fy_N,fz_N
  std::vector<TraceSample> samples;              // time strictly increasing, repairs included
  std::vector<std::string> repairs;              // one human-readable line per repair made
};

struct TraceOptions {
  // A gap between two samples up to this long (seconds) is filled by linear interpolation at
  // the nominal rate instead of being refused; 0 repairs nothing.
  double max_repair_gap_s = 0;
};

// The Falcon's workspace in libnifalcon's device frame (metres) and its force limit.
constexpr double kFalconMinXY_m = -0.060, kFalconMaxXY_m = 0.060;
constexpr double kFalconMinZ_m = 0.075, kFalconMaxZ_m = 0.175;
constexpr double kFalconMaxForce_N = 8.9;
// rate_hz must lie in this range: a sample rate near the Falcon's 1 kHz servo loop.
constexpr double kTraceMinRate_hz = 900, kTraceMaxRate_hz = 1100;

// Reads and validates a trace file; throws InputError on any problem.
Trace load_trace(const std::string& path, const TraceOptions& options = {});
// The same for text already in memory; `path` names it in messages.
Trace parse_trace(const std::string& text, const std::string& path, const TraceOptions& options = {});

}  // namespace bleedsim
