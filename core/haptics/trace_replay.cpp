#include "core/haptics/trace_replay.h"

#include <algorithm>
#include <stdexcept>

namespace bleedsim {

DeviceSample trace_sample_at_tick(const Trace& trace, std::int64_t tick) {
  const std::vector<TraceSample>& s = trace.samples;
  if (s.empty()) throw std::invalid_argument("a trace to replay needs samples");
  if (tick < 0) throw std::invalid_argument("haptic ticks count from 0");
  const double t = s.front().t_s + double(tick) / kHapticRate_hz;
  const auto after = std::upper_bound(s.begin(), s.end(), t, [](double t, const TraceSample& x) { return t < x.t_s; });
  const TraceSample& a = *std::prev(after);
  DeviceSample sample;
  sample.position_m = {a.x_m, a.y_m, a.z_m};
  sample.buttons = a.buttons;
  if (after != s.end()) {
    const TraceSample& b = *after;
    const double w = (t - a.t_s) / (b.t_s - a.t_s);
    sample.position_m += w * (Eigen::Vector3d(b.x_m, b.y_m, b.z_m) - sample.position_m);
  }
  return sample;
}

}  // namespace bleedsim
