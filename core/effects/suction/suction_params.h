#pragma once
// The instrument in the blood (docs/bleeding.md, "Suction" and "Contact"): a suction that takes
// blood near its tip, and the tip's body that the blood parts around. The instrument is the stylus
// (a scene with [haptics]: its trace, or the host's samples) or, in a scene without one, a
// scripted path of [[tip]] points.
#include <cstdint>
#include <vector>

#include "core/runtime/params.h"

namespace bleedsim {

struct Scene;

// Present in a Scene only when the scene calls for suction; needs [particles] and an instrument.
struct SuctionParams {
  double radius_mm = 1.5;             // particle centres within this of the tip are within reach
  double max_flow_mm3_per_s = 30.0;   // the most blood it takes a second
  std::uint8_t buttons = 0x2;         // with the stylus: the grip buttons that turn it on, in contact
};

// Present in a Scene only when the instrument's tip parts the blood; needs [particles] and an instrument.
struct ContactParams {
  double tip_radius_mm = 1.0;  // the tip's body on the panel: a disc no particle enters
};

// A point of a scripted instrument's path: its tip at (x, y) at time t, in contact with the tissue
// from the first point's time to the last's, moving in straight lines between points.
struct TipPoint {
  double t_s = 0.0;
  double x_mm = 0.0;
  double y_mm = 0.0;
};

const ParamTable<SuctionParams>& suction_table();
const ParamTable<ContactParams>& contact_table();
// The [[tip]] tables; a point's key in messages is "tip[i]".
const ParamTable<TipPoint>& tip_table();

// What is wrong with a scene's path as a whole (its points one by one are tip_table()'s): fewer
// than two points, times not increasing, a path beside the stylus, a path nothing uses. Blames
// the point at fault ("tip[3].t_s"), or "tip".
ParamProblem tip_path_problem(const Scene& scene);

}  // namespace bleedsim
