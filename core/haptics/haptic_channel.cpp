#include "core/haptics/haptic_channel.h"

#include <cstring>

#include "core/runtime/hash.h"

namespace bleedsim {

const std::vector<HapticColumn>& haptic_columns() {
  using T = HapticColumn::Type;
  static const std::vector<HapticColumn> columns = {
      {"time", T::f64, 1, "s", "simulated time of the tick: tick n at n / 1000 s",
       [](const HapticTick& t, double* v) { v[0] = t.t_s; }},
      {"tool_position", T::f64, 3, "m", "the stylus tip in the device frame (libnifalcon: x right, y up, z towards the user)",
       [](const HapticTick& t, double* v) { Eigen::Vector3d::Map(v) = t.tool_m; }},
      {"panel_position", T::f64, 2, "mm", "the point of the tissue panel under the tip (x right, y down); on a mesh, in its texture",
       [](const HapticTick& t, double* v) { Eigen::Vector2d::Map(v) = t.panel_mm; }},
      {"buttons", T::u8, 1, "", "grip buttons held: bitmask 0x1, 0x2, 0x4, 0x8",
       [](const HapticTick& t, double* v) { v[0] = t.buttons; }},
      {"contact", T::u8, 1, "", "1 when the tip is in the tissue (below its surface, over the panel)",
       [](const HapticTick& t, double* v) { v[0] = t.contact; }},
      {"penetration", T::f64, 1, "m", "depth of the tip below the tissue surface; 0 out of contact",
       [](const HapticTick& t, double* v) { v[0] = t.penetration_m; }},
      {"force", T::f64, 3, "N", "force sent to the device, device frame: spring plus damper along the surface "
                                 "normal, clamped to the device's maximum",
       [](const HapticTick& t, double* v) { Eigen::Vector3d::Map(v) = t.force_N; }},
      {"cutting", T::u8, 1, "", "1 when in contact with a cutting button held: the tip cuts",
       [](const HapticTick& t, double* v) { v[0] = t.cutting; }},
  };
  return columns;
}

std::vector<std::uint8_t> haptic_column_bytes(const HapticColumn& column, const std::vector<HapticTick>& ticks) {
  const std::size_t value_bytes = column.type == HapticColumn::Type::f64 ? sizeof(double) : 1;
  std::vector<std::uint8_t> bytes(ticks.size() * std::size_t(column.components) * value_bytes);
  std::uint8_t* out = bytes.data();
  for (const HapticTick& tick : ticks) {
    double v[3];
    column.values(tick, v);
    for (int c = 0; c < column.components; ++c, out += value_bytes) {
      // x86-64 and the GPU machine's hosts are little-endian, as the files are.
      if (column.type == HapticColumn::Type::f64) std::memcpy(out, &v[c], sizeof(double));
      else *out = std::uint8_t(v[c]);
    }
  }
  return bytes;
}

std::uint64_t haptic_channel_hash(const std::vector<HapticTick>& ticks) {
  std::uint64_t hash = fnv1a64(nullptr, 0);
  for (const HapticColumn& column : haptic_columns()) {
    const std::vector<std::uint8_t> bytes = haptic_column_bytes(column, ticks);
    hash = fnv1a64(bytes.data(), bytes.size(), hash);
  }
  return hash;
}

}  // namespace bleedsim
