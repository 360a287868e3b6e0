#include "core/scene/tool.h"

#include <algorithm>

namespace bleedsim {

std::optional<ToolSample> tool_at(const std::vector<ToolSample>& samples, double t_s, bool hold) {
  // The first sample later than t; the one before it is at or before t.
  const auto after = std::upper_bound(samples.begin(), samples.end(), t_s,
                                      [](double t, const ToolSample& s) { return t < s.t_s; });
  if (after == samples.begin()) return std::nullopt;
  ToolSample at = *(after - 1);
  if (after == samples.end()) {
    if (!hold && t_s > at.t_s) return std::nullopt;
    return at;
  }
  const double share = (t_s - at.t_s) / (after->t_s - at.t_s);
  at.x_mm += share * (after->x_mm - at.x_mm);
  at.y_mm += share * (after->y_mm - at.y_mm);
  at.t_s = t_s;
  return at;
}

std::vector<ToolSample> scripted_tool(const std::vector<TipPoint>& path) {
  std::vector<ToolSample> samples;
  for (const TipPoint& p : path) samples.push_back({p.t_s, p.x_mm, p.y_mm, true, kEveryButton});
  return samples;
}

}  // namespace bleedsim
