#include "core/haptics/haptic_params.h"

#include <cmath>

#include "core/runtime/message_text.h"
#include "core/scene/scene.h"
#include "core/scene/trace.h"

namespace bleedsim {
namespace {

using P = HapticParams;

// A file that places no origin puts the device's x = y = 0 over the panel's centre.
ParamProblem origin_at_centre(P& h, const Written& written, const Scene& scene) {
  if (!written.has("panel_origin_mm")) {
    h.origin_x_mm = scene.domain.width_mm / 2;
    h.origin_y_mm = scene.domain.height_mm / 2;
  }
  return {};
}

ParamProblem passive(const P& h, const Scene&) { return passivity_problem(h); }

// The spring's share of passivity's demand, k·T/2: what sampling at T adds.
double spring_share(double stiffness_N_per_m) { return stiffness_N_per_m * kHapticPeriod_s / 2; }

}  // namespace

double passivity_demand_Ns_per_m(const HapticParams& p) { return spring_share(p.stiffness_N_per_m) + std::abs(p.damping_Ns_per_m); }

double passive_damping_limit_Ns_per_m(double stiffness_N_per_m, double device_damping_Ns_per_m) {
  return device_damping_Ns_per_m - spring_share(stiffness_N_per_m);
}

ParamProblem passivity_problem(const HapticParams& p) {
  const double needed = passivity_demand_Ns_per_m(p);
  if (needed < p.device_damping_Ns_per_m) return {};
  const char* key = spring_share(p.stiffness_N_per_m) >= p.device_damping_Ns_per_m ? "stiffness_N_per_m" : "damping_Ns_per_m";
  return {key, "k·T/2 + |b| = " + format_number(spring_share(p.stiffness_N_per_m)) + " + " + format_number(p.damping_Ns_per_m) +
                   " = " + format_number(needed) + " N·s/m is not below the device's damping of " +
                   format_number(p.device_damping_Ns_per_m) +
                   " N·s/m: at 1 kHz the contact could feed energy into the stylus and buzz (passivity "
                   "bound of Colgate & Schenkel, b_device > k·T/2 + |b|, T = 1 ms); lower "
                   "stiffness_N_per_m or damping_Ns_per_m"};
}

const ParamTable<HapticParams>& haptic_table() {
  using T = ParamType;
  static const ParamTable<P> table{
      "haptics",
      "a recorded Falcon trace replayed through the 1 kHz haptic loop: its stylus cuts the tissue",
      {{"trace", T::text, {}, "", {}, "the trace file (docs/traces.md), relative to the scenario file", nullptr, true},
       {"repair_gap_ms", T::number, {}, "ms", {0, 1000},
        "dropouts in the trace up to this long are filled by linear interpolation; 0 repairs none", "0"},
       {"surface_z_mm", T::number, BLEEDSIM_MEMBER(P, surface_z_mm), "mm", {1000 * kFalconMinZ_m, 1000 * kFalconMaxZ_m},
        "the tissue is the plane z = surface_z_mm of the device frame; the tip touches it below"},
       {"panel_origin_mm", T::vector, BLEEDSIM_VECTOR(P, origin_x_mm, origin_y_mm), "mm", {-1e4, 1e4},
        "the panel point under device x = y = 0", "the panel's centre"},
       {"scale", T::number, BLEEDSIM_MEMBER(P, scale), "", {0, 100, true},
        "panel mm per device mm: panel = origin + scale · (x, −y)"},
       {"stiffness_N_per_m", T::number, BLEEDSIM_MEMBER(P, stiffness_N_per_m), "N/m", {0, 3000, true},
        "the contact's spring along the surface normal"},
       {"damping_Ns_per_m", T::number, BLEEDSIM_MEMBER(P, damping_Ns_per_m), "N·s/m", {0, 20},
        "the contact's damper on the tip's normal speed"},
       {"device_damping_Ns_per_m", T::number, BLEEDSIM_MEMBER(P, device_damping_Ns_per_m), "N·s/m", {0, 20, true},
        "the Falcon's own damping, for the passivity bound"},
       {"max_force_N", T::number, BLEEDSIM_MEMBER(P, max_force_N), "N", {0, kFalconMaxForce_N, true},
        "the force sent to the device is clamped to this"},
       {"cut_button", T::integer, BLEEDSIM_MEMBER(P, cut_buttons), "", {1, 15},
        "bitmask of the grip buttons that cut while held in contact"},
       {"cut_spacing_mm", T::number, BLEEDSIM_MEMBER(P, cut_spacing_mm), "mm", {0.05, 100},
        "a cut every this much of the tip's path on the panel"}},
      {{"passive at 1 kHz: k·T/2 + |b| < device_damping_Ns_per_m (Colgate & Schenkel)", passive}},
      origin_at_centre};
  return table;
}

}  // namespace bleedsim
