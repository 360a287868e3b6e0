#include "core/runtime/scene.h"

#include <cmath>

namespace bleedsim {

PixelGrid Domain::grid() const {
  return PixelGrid{width_px, height_px, static_cast<float>(width_mm / width_px),
                   static_cast<float>(height_mm / height_px)};
}

int Scene::frame_count() const {
  return static_cast<int>(std::llround(duration_s * frame_rate_hz));
}

double Scene::frame_time_s(std::int64_t k) const {
  return static_cast<double>(k + 1) / frame_rate_hz;
}

SourcePlace Scene::place_of(const std::string& key) const {
  const auto it = places.find(key);
  return it != places.end() ? it->second : SourcePlace{source_path, 0, 0};
}

Cut Scene::cut_at(double x_mm, double y_mm, double start_s) const {
  const SpreadParams size = spread.value_or(SpreadParams{});
  const ParticleParams flow = particles.value_or(ParticleParams{});
  return Cut{x_mm, y_mm, start_s, size.radius_mm, size.growth_per_s, flow.rate_per_s, flow.bleed_s};
}

std::int64_t Scene::haptic_ticks_through_frame(std::int64_t k) const {
  // (k + 1) · rate is exact; one division, correctly rounded, and floor: the same on every host.
  return static_cast<std::int64_t>(std::floor(static_cast<double>((k + 1) * kHapticRate_hz) / frame_rate_hz)) + 1;
}

}  // namespace bleedsim
