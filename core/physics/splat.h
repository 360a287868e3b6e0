#pragma once
// Splat (the report's render-to-texture, §2.2.2.4): each live particle deposits its blood as a
// film over the panel, thickest under its centre and falling smoothly to nothing at the splat
// radius, so a pile reads as one continuous layer rather than dots.
//
// A particle of volume V weighs each pixel whose centre lies at distance d < R from its own by
//   w(d) = (1 − d²/R²)²,
// and the pixel receives the share w / S of its blood, S = Σ w over those pixels:
//   h += V · fade · w / (S · pixel area)   millimetres,
// so the film holds exactly V · fade on any pixel pitch: on pixels much finer than R this is the
// analytic V · fade · w / (π R²/3); on pixels as coarse as the splat it still holds the whole
// volume, where a fixed scale would deposit anywhere from none of it to several times it. A splat
// that reaches no pixel centre (S = 0: it falls between them, or R is under a pixel) puts all of
// its blood into the pixel holding its centre. A splat cut by the panel's edge keeps its whole
// volume on the panel, spread over the pixels inside: blood at the edge is blood on the panel.
//
// On a tissue mesh (core/physics/surface.h) distances are the surface's, through the frame of the
// particle's texel, so a footprint is an ellipse on the panel; and a pixel's film is its blood over
// its area on the surface, the panel's pixel area times the texel's stretch det J.
//
// Deposits are summed in fixed point, 64-bit integer units of kSplatUnitMm: integer addition is
// associative, so the CPU's loop and the GPU's atomics give the same sum in any order. The
// weights are whole units too, so S is exact and a particle's deposits add up to its blood to
// their own rounding alone: each is off by at most half a unit.
#include <cstddef>
#include <cstdint>

#include "core/physics/blur.h"
#include "core/physics/hd.h"
#include "core/physics/particle_state.h"
#include "core/physics/pixel_grid.h"
#include "core/physics/surface.h"

namespace bleedsim {

// 2⁻²⁴ mm (6e-8 mm, far below anything visible).
constexpr float kSplatUnitMm = 1.0f / 16777216.0f;
constexpr float kSplatUnitsPerMm = 16777216.0f;
// A particle's whole blood in one pixel at most, in units (more is clamped before it becomes an
// integer; the particles' rule deposit_fits keeps a scene below it).
constexpr float kMaxDepositUnits = 1.0e9f;
// A footprint weight w ∈ [0, 1] in whole units of 2⁻²³, rounded half up (2²³ · w + ½ is exact in
// float from one unit up, so the rounding is exactly half up there).
constexpr float kSplatWeightUnits = 8388608.0f;

// The sum is kept in tiles of kSplatTilePx × kSplatTilePx pixels, each stamped with the number of
// the last frame whose deposits could reach it. The conversion reads back only the tiles stamped
// this frame (elsewhere the film is zero) and leaves their sums zero again as it reads them: the
// sum is zero between frames. On the flat panel it writes the film of a tile stamped neither this
// frame nor the frame before not at all: a frame's conversion wrote its zeros already, and only the
// splat writes the film. So the splat moves the bytes under the blood, not the panel's. Stamps are
// only compared for equality, so they may wrap: a stale stamp that matches costs a read or a write
// of zeros, never a byte.
constexpr int kSplatTilePx = 32;

struct SplatTiles {
  std::uint32_t* stamp = nullptr;  // one a tile, row by row; before the first frame, all now − 1
  int across = 0;                  // tiles in a row
  std::uint32_t now = 1;           // this frame's stamp: one more than the frame before's
};

inline int splat_tiles_across(const PixelGrid& g) { return (g.width + kSplatTilePx - 1) / kSplatTilePx; }
inline std::size_t splat_tile_count(const PixelGrid& g) {
  return std::size_t(splat_tiles_across(g)) * std::size_t((g.height + kSplatTilePx - 1) / kSplatTilePx);
}

BLEEDSIM_HD inline int splat_tile(const SplatTiles& t, int i, int j) {
  return (j / kSplatTilePx) * t.across + i / kSplatTilePx;
}
// Whether this frame's deposits may have reached tile `tile`: elsewhere the sum is zero.
BLEEDSIM_HD inline bool stamped_now(const SplatTiles& t, int tile) { return t.stamp[tile] == t.now; }
// Whether the frame before's may have (and this frame's not): its film may be other than zero.
BLEEDSIM_HD inline bool stamped_before(const SplatTiles& t, int tile) { return t.stamp[tile] == t.now - 1u; }

// The splat's constants for a run, made on the host.
struct SplatModel {
  float radius_mm;      // R
  float radius_sq;      // R²
  float units_per_mm3;  // kSplatUnitsPerMm / pixel area: film units of one mm³ of blood in one pixel
  float particle_volume_mm3;
};

struct SplatArgs {
  ParticleLifetime lifetime;
  SplatModel splat;
  const float* position;    // the ring buffer's slots
  const std::uint32_t* age;
  int capacity;
  PixelGrid grid;
  std::uint64_t* units;     // grid.width × grid.height: the sum, in kSplatUnitMm; all zero between frames
  float* thickness_mm;      // the same, in mm
  SplatTiles tiles;         // where the sum may be other than zero
  SurfaceMap surface = {};  // a tissue mesh's maps; empty on the flat panel
  // In a scene with [blur], the blur's first pass (its film is thickness_mm): the film, once
  // converted, downsampled in the same pass, to BlurDownsample's bytes. None while `low` is null.
  BlurArgs downsample = {};
};

// The footprint's shape at squared distance d2: 1 at the centre, 0 (with zero slope) at R.
BLEEDSIM_HD inline float splat_weight(const SplatModel& s, float d2) {
  if (d2 >= s.radius_sq) return 0.0f;
  const float q = 1.0f - d2 / s.radius_sq;
  return q * q;
}

BLEEDSIM_HD inline std::uint64_t weight_units(float w) { return std::uint64_t(w * kSplatWeightUnits + 0.5f); }

// A particle's blood, V · fade, as film units in a single pixel, rounded half up.
BLEEDSIM_HD inline std::uint64_t blood_units(const SplatModel& s, float fade) {
  return std::uint64_t(min_float(s.particle_volume_mm3 * fade * s.units_per_mm3, kMaxDepositUnits) + 0.5f);
}

// The pixels a splat at (x, y) may reach: those whose centres lie within R, on the panel; and the
// surface's frame there (the identity on the flat panel).
struct SplatFootprint {
  float x, y;
  int i0, i1, j0, j1;  // inclusive; empty when i1 < i0 or j1 < j0
  SurfaceFrame frame;
};

BLEEDSIM_HD inline SplatFootprint splat_footprint(const SplatModel& s, const PixelGrid& g, float x, float y,
                                                  const SurfaceMap& surface = {}) {
  const float w = float(g.width), h = float(g.height);
  SurfaceFrame frame{1.0f, 0.0f, 1.0f};
  float rx = s.radius_mm, ry = s.radius_mm;
  if (curved(surface)) {
    frame = frame_at(surface, x, y);
    panel_reach(frame, s.radius_mm, &rx, &ry);
  }
  // Clamped before the conversions: float→int of out-of-range values differs between CPU and GPU.
  return {x, y,
          int(clamp_float(ceilf((x - rx) / g.mm_per_px_x - 0.5f), 0.0f, w)),
          int(clamp_float(floorf((x + rx) / g.mm_per_px_x - 0.5f), -1.0f, w - 1.0f)),
          int(clamp_float(ceilf((y - ry) / g.mm_per_px_y - 0.5f), 0.0f, h)),
          int(clamp_float(floorf((y + ry) / g.mm_per_px_y - 0.5f), -1.0f, h - 1.0f)),
          frame};
}

// Calls visit(pixel, weight in units) for each pixel of the footprint, rows top to bottom, each
// left to right: both sweeps of a particle see the same weights in the same order.
template <class Visit>
BLEEDSIM_HD inline void for_each_weight(const SplatModel& s, const PixelGrid& g, const SplatFootprint& f, bool curved,
                                        Visit visit) {
  for (int j = f.j0; j <= f.j1; ++j) {
    const float py = pixel_centre_y_mm(g, j) - f.y;
    for (int i = f.i0; i <= f.i1; ++i) {
      float dx = pixel_centre_x_mm(g, i) - f.x, dy = py;
      if (curved) to_surface(f.frame, dx, dy, &dx, &dy);
      visit(std::size_t(j) * std::size_t(g.width) + std::size_t(i), weight_units(splat_weight(s, dx * dx + dy * dy)));
    }
  }
}

// A particle's shares are blood · weight / total, rounded half up: the integer quotient
//   ⌊(2 · blood · weight + total) / (2 · total)⌋,
// exact, so the same on both backends. A 64-bit integer division is a long subroutine on the GPU,
// so the quotient is estimated in double from the particle's one reciprocal and then corrected.
// blood < 2³⁰ and weight ≤ 2²³ keep the numerator below 2⁵⁵, and 2 · total (a footprint's whole
// units) is exact in double. The estimate carries three roundings, each of relative size ≤ 2⁻⁵³,
// so it lies within 2³⁰ · 3 · 2⁻⁵³ < 2⁻²¹ of the quotient: truncated, it is off by at most one,
// either way, and one comparison each way makes it exact.
struct ShareDivisor {
  std::uint64_t twice_total;
  double inverse;  // 1 / (2 · total), rounded
};

BLEEDSIM_HD inline ShareDivisor share_divisor(std::uint64_t total) { return {2 * total, 1.0 / double(2 * total)}; }

BLEEDSIM_HD inline std::uint64_t share_of(std::uint64_t blood, std::uint64_t weight, const ShareDivisor& d) {
  const std::uint64_t numerator = 2 * blood * weight + d.twice_total / 2;
  std::uint64_t quotient = std::uint64_t(double(numerator) * d.inverse);
  if (quotient * d.twice_total > numerator)
    --quotient;
  else if (numerator - quotient * d.twice_total >= d.twice_total)
    ++quotient;
  return quotient;
}

// A footprint of up to this many pixels keeps its weights from the first sweep for the second (a
// weight is at most 2²³ units: 32 bits hold it); a larger one computes them again, the same.
constexpr int kKeptWeights = 32;

// Calls stamp(tile) for each tile the particle's blood may reach, then deposit(pixel, units) for
// each pixel that receives a share of the particle in `slot`: one sweep sums its footprint's
// weights, a second hands out the blood in proportion.
template <class Deposit, class Stamp>
BLEEDSIM_HD inline void splat_particle(const SplatArgs& a, int slot, Deposit deposit, Stamp stamp) {
  const std::uint32_t age = a.age[slot];
  if (!is_alive(a.lifetime, age)) return;
  const std::uint64_t blood = blood_units(a.splat, fade_alpha(a.lifetime, age));
  if (blood == 0) return;
  const float x = a.position[2 * slot], y = a.position[2 * slot + 1];
  const SplatFootprint f = splat_footprint(a.splat, a.grid, x, y, a.surface);
  const bool on_mesh = curved(a.surface);
  // In 64 bits: a panel may be 65,535 pixels a side. Also true when the footprint is empty.
  const bool keep = std::int64_t(f.i1 - f.i0 + 1) * std::int64_t(f.j1 - f.j0 + 1) <= kKeptWeights;
  std::uint32_t kept[kKeptWeights];
  int visited = 0;
  std::uint64_t total = 0;
  for_each_weight(a.splat, a.grid, f, on_mesh, [&](std::size_t, std::uint64_t w) {
    total += w;
    if (keep) kept[visited++] = std::uint32_t(w);
  });
  if (total == 0) {
    const PixelAt p = pixel_at(a.grid, x, y);
    stamp(splat_tile(a.tiles, p.i, p.j));
    deposit(std::size_t(p.j) * std::size_t(a.grid.width) + std::size_t(p.i), blood);
    return;
  }
  for (int tj = f.j0 / kSplatTilePx; tj <= f.j1 / kSplatTilePx; ++tj)
    for (int ti = f.i0 / kSplatTilePx; ti <= f.i1 / kSplatTilePx; ++ti) stamp(tj * a.tiles.across + ti);
  const ShareDivisor divisor = share_divisor(total);
  const auto hand_out = [&](std::size_t pixel, std::uint64_t w) {
    if (w == 0) return;  // share_of(blood, 0, ·) is 0: a footprint's corners outside R cost nothing
    const std::uint64_t units = share_of(blood, w, divisor);
    if (units != 0) deposit(pixel, units);
  };
  if (!keep) {
    for_each_weight(a.splat, a.grid, f, on_mesh, hand_out);
    return;
  }
  visited = 0;
  for (int j = f.j0; j <= f.j1; ++j)
    for (int i = f.i0; i <= f.i1; ++i) hand_out(std::size_t(j) * std::size_t(a.grid.width) + std::size_t(i), kept[visited++]);
}

BLEEDSIM_HD inline float thickness_from_units(std::uint64_t units) { return float(units) * kSplatUnitMm; }

// Pixel p's film, in mm: its sum converted, or zero where this frame's deposits did not reach
// (`reached` false: the sum there is zero, and is not read); on a mesh, over the pixel's area on the
// surface. The twins convert a tile at a time, asking its stamp once, and set each sum they read
// back to zero.
BLEEDSIM_HD inline float film_mm(const SplatArgs& a, std::size_t p, bool reached) {
  const float film = reached ? thickness_from_units(a.units[p]) : 0.0f;
  return curved(a.surface) ? film / area_stretch(frame_of(a.surface, p)) : film;
}

// Whether tile `tile`'s film is all zero this frame, its sum unread: no deposit reached it, on the
// flat panel (on a mesh a zero film is 0 over each pixel's area, which the twins compute).
BLEEDSIM_HD inline bool film_is_zero(const SplatArgs& a, int tile) {
  return !stamped_now(a.tiles, tile) && !curved(a.surface);
}
// Whether its film is in place already: zero now, and zero the frame before, whose conversion wrote
// those zeros (only the splat writes its film).
BLEEDSIM_HD inline bool film_in_place(const SplatArgs& a, int tile) {
  return film_is_zero(a, tile) && !stamped_before(a.tiles, tile);
}

// The stage's twins: deposit every live particle (a loop on the CPU, integer atomics on the GPU),
// then convert the sum to millimetres, leaving it zero (and downsample the film, when asked). Each
// call is a frame: the caller zeroes the sum before the first and gives each call the stamp after
// the last one's.
void cpu_twin(const SplatArgs& args, int threads);
void cuda_twin(const SplatArgs& args);

}  // namespace bleedsim
