#include "core/bleeding/cut_flow.h"

#include <algorithm>
#include <cmath>

namespace bleedsim {

double cut_blood_mm3(const Cut& cut, double t_s, const Heartbeat* beat) {
  const double bleeding_s = std::clamp(t_s - cut.start_s, 0.0, cut.bleed_s);
  const double flowing_s = cut.arterial && beat ? pulsed_flowing_s(*beat, cut.start_s, bleeding_s, cut.clot_s)
                           : cut.clot_s > 0.0   ? cut.clot_s * -std::expm1(-bleeding_s / cut.clot_s)
                                                : bleeding_s;
  return cut.wound_mm * cut.vessel_density * cut.flow_mm3_per_s_per_mm * flowing_s;
}

double cut_exit_speed_scale(const Cut& cut, double t_s, const Heartbeat* beat) {
  return cut.arterial && beat ? pulse_waveform(*beat, t_s) : 1.0;
}

}  // namespace bleedsim
