#pragma once
// Splat (the report's render-to-texture, §2.2.2.4): each live particle deposits its blood as a
// film over the panel, thickest under its centre and falling smoothly to nothing at the splat
// radius, so a pile reads as one continuous layer rather than dots.
//
// A particle of volume V at distance d from a pixel's centre adds
//   V · fade · w(d) / A,   w(d) = (1 − d²/R²)²  for d < R,   A = ∫ w dA = π R² / 3,
// millimetres of blood: the footprint integrates to V, so the field holds the blood's volume
// (fade aside). Deposits are summed in fixed point, 64-bit integer units of kSplatUnitMm: integer
// addition is associative, so the CPU's loop and the GPU's atomics give the same sum in any order.
#include <cstddef>
#include <cstdint>

#include "core/physics/hd.h"
#include "core/physics/particles.h"
#include "core/physics/pixel_grid.h"

namespace bleedsim {

// 2⁻²⁴ mm (6e-8 mm, far below anything visible).
constexpr float kSplatUnitMm = 1.0f / 16777216.0f;
constexpr float kSplatUnitsPerMm = 16777216.0f;
// One deposit at most, in units (a deposit beyond it is clamped before it becomes an integer).
constexpr float kMaxDepositUnits = 1.0e9f;

// The splat's constants for a run, made on the host.
struct SplatModel {
  float radius_mm;         // R
  float radius_sq;         // R²
  float units_per_volume;  // kSplatUnitsPerMm / A: deposit units per mm³ at the centre
  float particle_volume_mm3;
};

struct SplatArgs {
  ParticleLifetime lifetime;
  SplatModel splat;
  const float* position;    // the ring buffer's slots
  const std::uint32_t* age;
  int capacity;
  PixelGrid grid;
  std::uint64_t* units;     // grid.width × grid.height: the sum, in kSplatUnitMm
  float* thickness_mm;      // the same, in mm
};

// The footprint's shape at squared distance d2: 1 at the centre, 0 (with zero slope) at R.
BLEEDSIM_HD inline float splat_weight(const SplatModel& s, float d2) {
  if (d2 >= s.radius_sq) return 0.0f;
  const float q = 1.0f - d2 / s.radius_sq;
  return q * q;
}

// Calls deposit(pixel, units) for each pixel whose centre lies within R of the particle in `slot`.
template <class Deposit>
BLEEDSIM_HD inline void splat_particle(const SplatArgs& a, int slot, Deposit deposit) {
  const std::uint32_t age = a.age[slot];
  if (!is_alive(a.lifetime, age)) return;
  const PixelGrid& g = a.grid;
  const float x = a.position[2 * slot], y = a.position[2 * slot + 1];
  const float w = float(g.width), h = float(g.height), r = a.splat.radius_mm;
  // Clamped before the conversions: float→int of out-of-range values differs between CPU and GPU.
  const int i0 = int(clamp_float(ceilf((x - r) / g.mm_per_px_x - 0.5f), 0.0f, w));
  const int i1 = int(clamp_float(floorf((x + r) / g.mm_per_px_x - 0.5f), -1.0f, w - 1.0f));
  const int j0 = int(clamp_float(ceilf((y - r) / g.mm_per_px_y - 0.5f), 0.0f, h));
  const int j1 = int(clamp_float(floorf((y + r) / g.mm_per_px_y - 0.5f), -1.0f, h - 1.0f));
  const float centre_units = a.splat.particle_volume_mm3 * fade_alpha(a.lifetime, age) * a.splat.units_per_volume;
  for (int j = j0; j <= j1; ++j) {
    const float dy = pixel_centre_y_mm(g, j) - y;
    for (int i = i0; i <= i1; ++i) {
      const float dx = pixel_centre_x_mm(g, i) - x;
      const float units = fminf(centre_units * splat_weight(a.splat, dx * dx + dy * dy), kMaxDepositUnits);
      const std::uint64_t whole = std::uint64_t(units + 0.5f);
      if (whole != 0) deposit(std::size_t(j) * std::size_t(g.width) + std::size_t(i), whole);
    }
  }
}

BLEEDSIM_HD inline float thickness_from_units(std::uint64_t units) { return float(units) * kSplatUnitMm; }

// The sum converted to millimetres, pixel by pixel (core/physics/pixel_kernels.h runs it).
struct SplatThickness {
  PixelGrid grid;
  const std::uint64_t* units;
  float* thickness_mm;

  BLEEDSIM_HD int width() const { return grid.width; }
  BLEEDSIM_HD int height() const { return grid.height; }
  BLEEDSIM_HD void operator()(int i, int j) const {
    const std::size_t p = std::size_t(j) * grid.width + i;
    thickness_mm[p] = thickness_from_units(units[p]);
  }
};

inline SplatThickness splat_thickness(const SplatArgs& a) { return {a.grid, a.units, a.thickness_mm}; }

// The stage's twins: clear the sum, deposit every live particle (a loop on the CPU, integer atomics
// on the GPU), then SplatThickness's twin.
void cpu_twin(const SplatArgs& args, int threads);
void cuda_twin(const SplatArgs& args);

}  // namespace bleedsim
