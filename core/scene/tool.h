#pragma once
// The instrument's motion (docs/bleeding.md, "The instrument"): samples of its tip on the panel,
// from the stylus (the haptic loop's ticks, or a host's own) or from a scenario's scripted path.
#include <optional>
#include <vector>

namespace bleedsim {

struct TipPoint;

// Where the tip is on the panel at t (mm), whether it touches the tissue, and whether its
// suction is on.
struct ToolSample {
  double t_s = 0.0;
  double x_mm = 0.0;
  double y_mm = 0.0;
  bool contact = false;
  bool suction = false;
};

// The tip at time t: on the straight line between the samples around t, with the flags of the one
// at or before it. After the last sample it stays there when `hold` (a stylus is where it was last
// seen), else it is gone (a scripted path has ended); before the first, it is nowhere.
std::optional<ToolSample> tool_at(const std::vector<ToolSample>& samples, double t_s, bool hold);

// A scripted path as samples: in contact, suction on, from its first point to its last.
std::vector<ToolSample> scripted_tool(const std::vector<TipPoint>& path);

}  // namespace bleedsim
