#pragma once
// A cut made by the tool: where and when, how large a stain it leaves (the spread's radius and
// growth rate), and how it bleeds particles: the mm of wound it stands for, the blood per second
// per mm of wound, for how long, and how fast the flow clots. A stroke's cuts share its wound: the
// haptic loop's cuts each stand for the path between them, so the flow follows the wound's length,
// not how finely it is cut. What a scenario's [[cut]] leaves out comes from the scene's [spread]
// and [particles] defaults (cut_at, core/effects/cuts.h); how it bleeds over time is
// core/bleeding/.

namespace bleedsim {

struct Cut {
  double x_mm = 0.0;
  double y_mm = 0.0;
  double start_s = 0.0;
  double radius_mm = 0.0;
  double growth_per_s = 0.0;
  double wound_mm = 1.0;              // the length of wound it stands for
  double flow_mm3_per_s_per_mm = 0.0;  // blood per second per mm of wound, as it starts
  double bleed_s = 0.0;               // how long it bleeds
  double clot_s = 0.0;                // the flow falls as exp(−t/clot_s); 0: it does not
  bool arterial = false;              // with [pulse]: its flow and exit speed follow the heartbeat
  double wound_angle_deg = 0.0;       // with [vessels]: the wound's direction, centred on (x, y)
  double vessel_density = 1.0;        // the mean vessel density along its wound (1 without [vessels])
};

}  // namespace bleedsim
