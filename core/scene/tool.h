#pragma once
// The instrument's motion (docs/bleeding.md, "The instrument"): samples of its tip on the panel,
// from the stylus (the haptic loop's ticks, or a host's own) or from a scenario's scripted path.
#include <cstdint>
#include <optional>
#include <vector>

namespace bleedsim {

// A point of a scripted instrument's path: its tip at (x, y) at time t, in contact with the tissue
// from the first point's time to the last's, moving in straight lines between points.
struct TipPoint {
  double t_s = 0.0;
  double x_mm = 0.0;
  double y_mm = 0.0;
};

// Every grip button of the Falcon (four): a scripted path holds them all, so whatever a tool's
// buttons are, it is on along the path.
constexpr std::uint8_t kEveryButton = 0xF;

// Where the tip is on the panel at t (mm), whether it touches the tissue, and which grip buttons
// are held: what turns a tool of the instrument on is its effect's to say (suction: its buttons, in
// contact).
struct ToolSample {
  double t_s = 0.0;
  double x_mm = 0.0;
  double y_mm = 0.0;
  bool contact = false;
  std::uint8_t buttons = 0;
};

// The tip at time t: on the straight line between the samples around t, with the flags of the one
// at or before it. After the last sample it stays there when `hold` (a stylus is where it was last
// seen), else it is gone (a scripted path has ended); before the first, it is nowhere.
std::optional<ToolSample> tool_at(const std::vector<ToolSample>& samples, double t_s, bool hold);

// A scripted path as samples: in contact, every button held, from its first point to its last.
std::vector<ToolSample> scripted_tool(const std::vector<TipPoint>& path);

}  // namespace bleedsim
