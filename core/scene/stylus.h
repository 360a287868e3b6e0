#pragma once
// The stylus a scene has (docs/haptics.md): where the tissue lies under the Novint Falcon, how the
// device's motion maps onto the panel, the contact's spring and damper, and the cutting buttons.
// Its table, with the passivity it must keep, is core/haptics/haptic_params.h.
#include <cstdint>

namespace bleedsim {

// The haptic loop's rate: tick n is at t = n / kHapticRate_hz, the Falcon's 1 kHz servo loop.
constexpr int kHapticRate_hz = 1000;
// Its period T.
constexpr double kHapticPeriod_s = 1.0 / kHapticRate_hz;

// Present in a Scene only when the scene calls for the stylus. Positions in the device frame are
// libnifalcon's (x right, y up, z towards the user).
struct HapticParams {
  // Where the tissue lies: the plane z = surface_z_mm of the device frame; the tip is in it below.
  double surface_z_mm = 120.0;
  // How device motion maps onto the panel: panel = origin + scale · (x, −y), in mm (the panel's y
  // points down, the device's up). The origin is the panel point under device x = y = 0.
  double origin_x_mm = 0.0;
  double origin_y_mm = 0.0;
  double scale = 1.0;
  // The contact: a spring along the surface normal plus a damper, clamped to the device's maximum.
  double stiffness_N_per_m = 500.0;
  double damping_Ns_per_m = 0.5;
  double device_damping_Ns_per_m = 1.5;  // the Falcon's own, for the passivity bound
  double max_force_N = 8.0;
  // Cutting: a cut every cut_spacing_mm of the tip's path while one of these buttons is held in contact.
  std::uint8_t cut_buttons = 0x1;
  double cut_spacing_mm = 1.0;
};

}  // namespace bleedsim
