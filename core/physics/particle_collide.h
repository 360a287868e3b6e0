#pragma once
// Collide (core/physics/particles.h): what a particle's neighbours in the 3 × 3 cells around it add
// up to (the pair forces, a film with depth's depth and edge, the births' shift), in a fixed order.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/physics/counter_hash.h"
#include "core/physics/hd.h"
#include "core/physics/particle_bin.h"
#include "core/physics/particle_line.h"
#include "core/physics/particle_state.h"
#include "core/physics/surface.h"

namespace bleedsim {

// Particles at exactly the same point have no direction between them. Each particle has a heading
// of its own, a point of [−1, 1)² hashed from its slot, and a coincident pair is pushed apart along
// the line between the two headings: opposite for the two (a − b = −(b − a) in floating point), and
// for a whole cluster born at one point each particle's pairs add up to a push away from the
// others' headings, so the cluster spreads out instead of cancelling. (Equal headings, one pair in
// 2⁴⁸, part along x.)
BLEEDSIM_HD inline void coincident_direction(std::uint32_t slot, std::uint32_t other, float* nx, float* ny) {
  const auto heading = [](std::uint32_t s, std::uint32_t axis) { return signed_unit(mix32(mix32(s) ^ axis)); };
  const float dx = heading(slot, 0x68e31da4U) - heading(other, 0x68e31da4U);
  const float dy = heading(slot, 0xb5297a4dU) - heading(other, 0xb5297a4dU);
  const float length = sqrtf(dx * dx + dy * dy);
  if (length > 0.0f) {
    *nx = dx / length;
    *ny = dy / length;
  } else {
    *nx = slot < other ? 1.0f : -1.0f;
    *ny = 0.0f;
  }
}

// How much of the cohesion acts at distance r: all of it up to contact, then falling smoothly to
// nothing (with zero slope) at the range.
BLEEDSIM_HD inline float cohesion_share(const ParticleModel& m, float r) {
  if (r <= m.diameter_mm) return 1.0f;
  const float q = (m.range_mm - r) * m.band_inverse;
  return q * q;
}

// The film with depth (docs/particles.md#a-film-with-depth): a particle is a parcel of volume V of a
// shallow film whose depth is h(x) = Σ V·W(|x − x_j|), W the 2D Wendland C2 kernel of support R,
// W(q) = 7/(π·R²)·(1 − q)⁴·(1 + 4q). Its hydrostatic energy ½·ρ·g_n·Σ V·h_i, differentiated, pushes
// each parcel away from each neighbour by g_n·V·|∇W| = pressure·q·(1 − q)³: the pressure's
// gradient, −g_n·∇h, summed over pairs, which conserves momentum as the contact does. It is
// bounded (and 0 at q = 0), so parcels may overlap as deep as the film is.
//
// The kernel's slope, |dW/dr|, in units of its largest: q·(1 − q)³ (0 from the kernel's reach on).
BLEEDSIM_HD inline float kernel_slope(const ParticleModel& m, float r) {
  const float q = r * m.kernel_inverse;
  if (q >= 1.0f) return 0.0f;
  const float rest = 1.0f - q;
  return q * (rest * rest * rest);
}

BLEEDSIM_HD inline float film_push(const ParticleModel& m, float r) { return m.pressure * kernel_slope(m, r); }

// A parcel's depth at distance r from it: V·W(r) = parcel_depth·(1 − q)⁴·(1 + 4q).
BLEEDSIM_HD inline float parcel_depth_at(const ParticleModel& m, float r) {
  const float q = r * m.kernel_inverse;
  if (q >= 1.0f) return 0.0f;
  const float rest = 1.0f - q, rest_sq = rest * rest;
  return m.parcel_depth * (rest_sq * rest_sq) * (1.0f + 4.0f * q);
}

// What a particle's pairs add up to: its acceleration, the shift that undoes its overlaps with new
// particles, and how its neighbours lie around it.
struct PairSums {
  float ax = 0.0f, ay = 0.0f;  // mm/s²: the full-grown pairs' forces
  float depth = 0.0f;          // mm: a film with depth's depth here (bin's) ...
  float line = 0.0f;           // mm: ... and its share of the contact line (line_share)
  float hx = 0.0f, hy = 0.0f;  // mm: half of each overlap with a new particle, away from it
  bool crowded = false;        // a film with depth's birth: another birth nearer than kBirthsApart
  float sx = 0.0f, sy = 0.0f;  // the directions to the neighbours, weighted as the cohesion
  float company = 0.0f;        // the weights
  float fastest_sq = 0.0f;     // (mm/s)²: the fastest neighbour's speed
};

// The pair force on a particle from the one at offset (dx, dy) = p − q from it (per unit mass, on the
// surface), along their line of centres. Overlapping, a spring pushes them apart and a dashpot resists their approach, together
// never pulling (a dashpot that pulled separating particles would be a tension the blood does not
// have); within the range, cohesion pulls. The same arithmetic from either side gives equal and
// opposite forces, bit for bit.
// A pair with a new particle parts before it pushes (docs/particles.md#soft-births): while it is
// parting it has no force, and its overlap is undone by moving both particles apart, half of it
// each, at a limited speed (the shift, applied by integrate_particle), which gives them no velocity.
// Particles born on top of each other (a burst from one point) so part without being blasted apart.
// The contact's pairs part over the younger's first half of birth_steps and then grow into their
// force over the second, so the small overlaps left (a new particle resting on others) are taken
// up slowly, under drag, not released at once. A film with depth's births end by distance instead
// (collide_particle): two parcels being born part, two born ones push with their whole force, and a
// pair with a parcel joining after a crowded birth with the share the one that joined last has grown.
// Returns the share of its force a pair has, or kParting while it parts.
constexpr float kParting = -1.0f;
BLEEDSIM_HD inline float joined_share(const ParticleModel& m, std::uint32_t rest) {
  return joining(m, rest) ? min_float(1.0f, float(rest - kJoining) / m.join_steps) : 1.0f;
}
BLEEDSIM_HD inline float pair_growth(const ParticleModel& m, std::uint32_t birth, std::uint32_t other_birth) {
  if (has_depth(m)) {
    if (being_born(m, birth)) return kParting;
    return min_float(joined_share(m, birth), joined_share(m, other_birth));
  }
  const float younger = float(birth < other_birth ? birth : other_birth), half_birth = 0.5f * m.birth_steps;
  if (younger < half_birth) return kParting;
  return min_float(1.0f, (younger - half_birth) / half_birth);
}

BLEEDSIM_HD inline void add_pair(const ParticleModel& m, float dx, float dy, float vx, float vy, float growth,
                                 std::uint32_t slot, float wx, float wy, std::uint32_t other, PairSums* sums) {
  const float r2 = dx * dx + dy * dy;
  if (r2 >= m.range_sq) return;
  float nx, ny, r;
  if (r2 > 0.0f) {
    r = sqrtf(r2);
    const float r_inverse = 1.0f / r;  // one division for both components (and the same for the pair)
    nx = dx * r_inverse;
    ny = dy * r_inverse;
  } else {
    r = 0.0f;
    coincident_direction(slot, other, &nx, &ny);
  }
  const float share = cohesion_share(m, r);
  sums->fastest_sq = max_float(sums->fastest_sq, wx * wx + wy * wy);
  sums->sx += share * nx;
  sums->sy += share * ny;
  sums->company += share;
  if (growth == kParting) {
    const float half_overlap = 0.5f * max_float(m.diameter_mm - r, 0.0f);
    sums->hx += half_overlap * nx;
    sums->hy += half_overlap * ny;
    sums->crowded = sums->crowded || (has_depth(m) && r < kBirthsApart * m.diameter_mm);
    return;
  }
  float push = 0.0f;
  if (has_depth(m)) {
    push = film_push(m, r);
  } else if (r < m.diameter_mm) {
    const float approach = (vx - wx) * nx + (vy - wy) * ny;
    push = max_float(m.stiffness * (m.diameter_mm - r) - m.damping * approach, 0.0f);
  }
  const float force = growth * (push - m.cohesion * share);
  sums->ax += force * nx;
  sums->ay += force * ny;
}

// The mucosa's grip on a particle (docs/particles.md#the-mucosas-grip): static friction up to the
// yield for every particle, and up to the pinning besides for one on the film's edge (its
// neighbours all on one side, or too few to surround it), where the contact line holds. A film
// with depth has them as a stress and a force per unit length of the contact line: the parcel's
// area V/h bears the yield stress, and its share of the line (which the parcels' shares sum to),
// the pinning; per unit mass, (τ_y/ρ)/h + q_p·line/V.
BLEEDSIM_HD inline float grip_from(const ParticleModel& m, const PairSums& sums) {
  if (has_depth(m)) return m.yield_stress / sums.depth + m.line_grip * sums.line;
  const bool on_edge = sums.sx * sums.sx + sums.sy * sums.sy > m.edge_openness * m.edge_openness ||
                       sums.company < m.edge_company;
  return on_edge ? m.yield + m.pinning : m.yield;
}

// A film with depth's births part sideways and downhill, never uphill: blood welling up from a
// wound runs down the tissue, and what it pressed uphill would be blood the wound never sent there.
BLEEDSIM_HD inline void drop_uphill(const ParticleModel& m, float* hx, float* hy) {
  const float along = *hx * m.gravity_x + *hy * m.gravity_y;
  if (along >= 0.0f) return;
  const float share = along / (m.gravity_x * m.gravity_x + m.gravity_y * m.gravity_y);
  *hx -= share * m.gravity_x;
  *hy -= share * m.gravity_y;
}

// A particle's acceleration and shift from its pair sums, the shift no longer than birth_speed·dt
// (so a burst parts at no more than that speed); its grip, and whether a neighbour moves fast
// enough to wake it or (a birth) one still being born crowds it.
BLEEDSIM_HD inline void finish_pair_sums(const ParticleArrays& p, const ParticleModel& m, std::uint32_t slot,
                                         const PairSums& sums) {
  float hx = sums.hx, hy = sums.hy;
  if (has_depth(m)) drop_uphill(m, &hx, &hy);
  const float most = m.birth_speed * m.dt_s, size_sq = hx * hx + hy * hy;
  if (size_sq > most * most) {
    const float scale = most / sqrtf(size_sq);
    hx *= scale;
    hy *= scale;
  }
  set_pair(p.acceleration, slot, {sums.ax, sums.ay});
  set_pair(p.shift, slot, {hx, hy});
  p.grip[slot] = grip_from(m, sums);
  p.neighbourhood[slot] = (sums.fastest_sq > m.wake_speed_sq ? kStirred : 0u) | (sums.crowded ? kCrowded : 0u);
}

// A film with depth meets the panel's edges as its own mirror image (docs/particles.md#walls-of-a-
// film-with-depth): each wall within the kernel of the parcel at p reflects the parcel at q (itself
// too), and the image pushes as a parcel would. The film's depth at a wall is then what the film
// would have if it went on past it, so a pool against a wall is as deep there as hydrostatics says
// (without images, it came out 27 % shallow), and the wall takes the push no parcel sends back.
// Both on the panel, q's image is never nearer p than q is, so the neighbours within the range hold
// every image that reaches p. An image at p itself (a parcel on the wall's line) has no direction
// and, on the line, no push to give. Of two opposite walls both within reach (a panel narrower than
// two ranges) only the low one mirrors.
template <class Visit>
BLEEDSIM_HD inline void for_each_wall_image(const ParticleModel& m, float px, float py, float qx, float qy,
                                            Visit visit) {
  const float reach = m.range_mm;
  // The image of q across a wall at w is 2w − q: p − (2w − q) = (p − w) + (q − w).
  const bool near_low_x = px - m.min_x < reach, near_high_x = m.max_x - px < reach;
  const bool near_low_y = py - m.min_y < reach, near_high_y = m.max_y - py < reach;
  const float ix = near_low_x ? (px - m.min_x) + (qx - m.min_x) : (px - m.max_x) + (qx - m.max_x);
  const float iy = near_low_y ? (py - m.min_y) + (qy - m.min_y) : (py - m.max_y) + (qy - m.max_y);
  const bool by_x = near_low_x || near_high_x, by_y = near_low_y || near_high_y;
  const auto image = [&](float dx, float dy) {
    const float r2 = dx * dx + dy * dy;
    if (r2 > 0.0f && r2 < m.range_sq) visit(dx, dy, r2);
  };
  if (by_x) image(ix, py - qy);
  if (by_y) image(px - qx, iy);
  if (by_x && by_y) image(ix, iy);
}

// An image of a parcel pushes as the parcel would.
BLEEDSIM_HD inline void add_wall_images(const ParticleModel& m, float px, float py, float qx, float qy, PairSums* sums) {
  for_each_wall_image(m, px, py, qx, qy, [&](float dx, float dy, float r2) {
    const float r = sqrtf(r2), push = film_push(m, r) / r;
    sums->ax += push * dx;
    sums->ay += push * dy;
  });
}

// Visits every neighbour of the particle at sorted position i within the range, in the 3 × 3 cells
// around its own: row by row, each row's cells left to right and their particles in sorted order
// (one run of the sorted order a row), as visit(j, qx, qy, dx, dy, r2) with (dx, dy) = p − q on
// the surface. No cap on a crowded cell: a pair is visited from both sides or from neither.
template <class Visit>
BLEEDSIM_HD inline void for_each_neighbour(const ParticleArrays& p, const ParticleModel& m, int i, Visit visit) {
  const std::uint32_t key = p.sorted_key[i];
  const int cx = int(key % std::uint32_t(m.cells_x));
  const int cy = int(key / std::uint32_t(m.cells_x));
  const auto [px, py] = pair_at(p.sorted_position, std::size_t(i));
  const int x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < m.cells_x ? cx + 1 : cx;
  const SurfaceFrame own = curved(m.surface) ? frame_at(m.surface, px, py) : SurfaceFrame{1.0f, 0.0f, 1.0f};
  for (int ny = cy - 1; ny <= cy + 1; ++ny) {
    if (ny < 0 || ny >= m.cells_y) continue;
    const SortedRun run = row_run(p, m, ny, x0, x1);
    for (std::uint32_t j = run.begin; j < run.end; ++j) {
      if (j == std::uint32_t(i)) continue;
      const auto [qx, qy] = pair_at(p.sorted_position, j);
      float dx = px - qx, dy = py - qy;
      if (curved(m.surface)) to_surface(pair_frame(own, frame_at(m.surface, qx, qy)), dx, dy, &dx, &dy);
      const float r2 = dx * dx + dy * dy;
      if (r2 < m.range_sq) visit(j, qx, qy, dx, dy, r2);
    }
  }
}

// A film with depth's depth at the particle at sorted position i (bin's last pass): its own parcel,
// its neighbours' and the walls' images of both, in the neighbours' order.
BLEEDSIM_HD inline void depth_particle(const ParticleArrays& p, const ParticleModel& m, int i) {
  if (p.sorted_key[i] == sentinel_key(m)) return;
  // Named, not bound: a lambda may not capture a structured binding before C++20 (clang refuses it).
  const FloatPair at = pair_at(p.sorted_position, std::size_t(i));
  const float px = at.x, py = at.y;
  float depth = m.parcel_depth;
  const auto add_images = [&](float qx, float qy) {
    for_each_wall_image(m, px, py, qx, qy, [&](float, float, float r2) { depth += parcel_depth_at(m, sqrtf(r2)); });
  };
  for_each_neighbour(p, m, i, [&](std::uint32_t, float qx, float qy, float, float, float r2) {
    depth += parcel_depth_at(m, sqrtf(r2));
    add_images(qx, qy);
  });
  add_images(px, py);
  p.sorted_depth[i] = depth;
}

// The pair forces on the particle at sorted position i from every neighbour within the range
// (for_each_neighbour). A neighbour's velocity and birth are read only once it is within the range
// (about a third of the particles of the 3 × 3 cells are), and its slot only when it coincides
// with this one (the slot names the pair's direction only then). A film with depth adds the walls'
// images and its share of the contact line. A parcel being born is in the film's depth and pushes the film as
// any parcel does, but the film does not push it back: it meets only the others being born, and
// they part (pair_growth). (Left out of the film, a burst was a hole the film around it ran into at
// twice g/γ; pushed by it, a burst into a pool is blasted as births by age were.)
BLEEDSIM_HD inline void collide_particle(const ParticleArrays& p, const ParticleModel& m, int i) {
  if (p.sorted_key[i] == sentinel_key(m)) return;
  const std::uint32_t slot = p.sorted_slot[i];
  const FloatPair at = pair_at(p.sorted_position, std::size_t(i));
  const FloatPair own_velocity = pair_at(p.sorted_velocity, std::size_t(i));
  const float px = at.x, py = at.y, vx = own_velocity.x, vy = own_velocity.y;
  const std::uint32_t birth = p.sorted_birth[i];
  const bool in_film = has_depth(m) && !being_born(m, birth);
  PairSums sums;
  if (has_depth(m)) sums.depth = p.sorted_depth[i];
  for_each_neighbour(p, m, i, [&](std::uint32_t j, float qx, float qy, float dx, float dy, float r2) {
    const std::uint32_t other_birth = p.sorted_birth[j];
    if (being_born(m, birth) && !being_born(m, other_birth)) return;
    const std::uint32_t other = r2 > 0.0f ? 0u : p.sorted_slot[j];
    const FloatPair w = pair_at(p.sorted_velocity, j);
    add_pair(m, dx, dy, vx, vy, pair_growth(m, birth, other_birth), slot, w.x, w.y, other, &sums);
    if (in_film) add_wall_images(m, px, py, qx, qy, &sums);
  });
  if (in_film) {
    add_wall_images(m, px, py, px, py, &sums);
    sums.line = line_share(p, m, px, py);
  }
  finish_pair_sums(p, m, slot, sums);
}

}  // namespace bleedsim
