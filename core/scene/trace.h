#pragma once
// A recorded Novint Falcon stylus trace, as samples in libnifalcon's frame and units, and the
// device's limits. Read from its CSV file by core/io/trace_csv.h (docs/traces.md).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

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
  std::vector<std::string> repairs;              // one human-readable line for each of the first repairs
  std::uint64_t repairs_made = 0;                // every repair, described or not
  double median_interval_s = 0;                  // of the intervals rate_hz was checked against
};

// The Falcon's workspace in libnifalcon's device frame (metres) and its force limit.
constexpr double kFalconMinXY_m = -0.060, kFalconMaxXY_m = 0.060;
constexpr double kFalconMinZ_m = 0.075, kFalconMaxZ_m = 0.175;
constexpr double kFalconMaxForce_N = 8.9;

}  // namespace bleedsim
