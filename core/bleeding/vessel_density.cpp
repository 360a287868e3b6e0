#include "core/bleeding/vessel_density.h"

#include <algorithm>
#include <cmath>

namespace bleedsim {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The map at (x, y) mm, bilinearly between pixel centres.
double density_at(const Scene& scene, double x_mm, double y_mm) {
  const Domain& d = scene.domain;
  const double u = std::clamp(x_mm * d.width_px / d.width_mm - 0.5, 0.0, double(d.width_px - 1));
  const double v = std::clamp(y_mm * d.height_px / d.height_mm - 0.5, 0.0, double(d.height_px - 1));
  const int i = std::max(0, std::min(int(u), d.width_px - 2)), j = std::max(0, std::min(int(v), d.height_px - 2));
  const int i1 = std::min(i + 1, d.width_px - 1), j1 = std::min(j + 1, d.height_px - 1);
  const double fx = u - i, fy = v - j;
  const auto at = [&](int a, int b) { return double(scene.vessel_density[std::size_t(b) * d.width_px + a]); };
  return (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i1, j)) + fy * ((1 - fx) * at(i, j1) + fx * at(i1, j1));
}

}  // namespace

double mean_vessel_density(const Scene& scene, double x0_mm, double y0_mm, double x1_mm, double y1_mm) {
  const Domain& d = scene.domain;
  const double pixel_mm = std::min(d.width_mm / d.width_px, d.height_mm / d.height_px);
  const double length = std::hypot(x1_mm - x0_mm, y1_mm - y0_mm);
  const int steps = std::max(1, int(std::ceil(4.0 * length / pixel_mm)));
  double sum = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double s = (k + 0.5) / steps;
    sum += density_at(scene, x0_mm + s * (x1_mm - x0_mm), y0_mm + s * (y1_mm - y0_mm));
  }
  return sum / steps;
}

double wound_vessel_density(const Scene& scene, const Cut& cut) {
  const double half = cut.wound_mm / 2.0, a = cut.wound_angle_deg * kDegree;
  const double dx = half * std::cos(a), dy = half * std::sin(a);
  return mean_vessel_density(scene, cut.x_mm - dx, cut.y_mm - dy, cut.x_mm + dx, cut.y_mm + dy);
}

}  // namespace bleedsim
