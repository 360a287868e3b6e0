// bleedsim trace info: what a recorded Falcon trace holds, after the loader has checked it.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/trace.h"

namespace bleedsim::cli {
namespace {

// The stretches during which the cutting button (0x1) is held.
struct Press {
  double start_s, end_s;
};

std::vector<Press> presses(const Trace& trace) {
  std::vector<Press> found;
  bool held = false;
  for (const TraceSample& s : trace.samples) {
    const bool now = s.buttons & 0x1;
    if (now && !held) found.push_back({s.t_s, s.t_s});
    if (now) found.back().end_s = s.t_s;
    held = now;
  }
  return found;
}

double median_interval_s(const Trace& trace) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < trace.samples.size(); ++i) dt.push_back(trace.samples[i].t_s - trace.samples[i - 1].t_s);
  if (dt.empty()) return 0.0;
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  return dt[dt.size() / 2];
}

}  // namespace

int trace_info_command(const std::string& path, double max_repair_gap_ms) {
  const Trace trace = load_trace(path, TraceOptions{max_repair_gap_ms / 1000.0});
  const std::vector<TraceSample>& s = trace.samples;
  const auto range = [&](double TraceSample::*axis) {
    const auto [low, high] = std::minmax_element(s.begin(), s.end(),
                                                 [&](const TraceSample& a, const TraceSample& b) { return a.*axis < b.*axis; });
    char text[64];
    std::snprintf(text, sizeof text, "%.1f to %.1f mm", 1000.0 * (*low).*axis, 1000.0 * (*high).*axis);
    return std::string(text);
  };
  const double interval = median_interval_s(trace);
  std::printf("%s: valid\n", path.c_str());
  std::printf("  device     %s\n", trace.metadata.count("device") ? trace.metadata.at("device").c_str() : "");
  std::printf("  samples    %zu over %.3f s (t = %.4f to %.4f s)\n", s.size(), s.back().t_s - s.front().t_s,
              s.front().t_s, s.back().t_s);
  std::printf("  rate       %g Hz stated, %.1f Hz measured (median interval %.4f ms)\n", trace.rate_hz,
              interval > 0 ? 1.0 / interval : 0.0, 1000.0 * interval);
  std::printf("  workspace  x %s, y %s, z %s\n", range(&TraceSample::x_m).c_str(), range(&TraceSample::y_m).c_str(),
              range(&TraceSample::z_m).c_str());
  std::printf("  force      %s\n", trace.has_force ? "recorded (fx_N, fy_N, fz_N)" : "not recorded");
  const std::vector<Press> cuts = presses(trace);
  std::printf("  cuts       %zu (button 0x1 held)", cuts.size());
  for (const Press& p : cuts) std::printf("%s %.3f-%.3f s", &p == &cuts.front() ? ":" : ",", p.start_s, p.end_s);
  std::printf("\n  gaps       %zu repaired\n", trace.repairs.size());
  for (const std::string& repair : trace.repairs) std::printf("    %s\n", repair.c_str());
  return 0;
}

}  // namespace bleedsim::cli
