#pragma once
// The instrument in the blood (docs/bleeding.md, "Suction" and "Contact"). Once a sub-step has
// moved the particles, the instrument's tip acts on them where it is at the step's end:
//   aspirate  the suction takes the particles whose centres lie within its reach, nearest first
//             (ties by slot), at most this step's quota of them: each is marked aspirated in its
//             age (kAspirated) and counted, and no longer lives, bins or splats
//   contact   the tip's body is a disc the blood parts around: a centre inside it is moved to the
//             nearest point outside it (and inside the panel), its velocity's approach to the tip
//             taken away; so no particle is inside the tip after a sub-step
// Nearest first is a selection of the quota smallest keys (distance², slot): unique keys, so the
// set is one and the same however a backend selects it (a partial sort on the CPU, a radix select
// on the GPU), and the distance is exact float arithmetic on both.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/physics/hd.h"
#include "core/physics/particles.h"

namespace bleedsim {

// The tip where it is at the end of this sub-step, in panel millimetres.
struct ToolTip {
  float x_mm, y_mm;
  float vx_mm_s, vy_mm_s;  // its velocity over the sub-step
  float reach_sq;          // aspirate: the suction's radius², for particle centres
  float body_mm;           // contact: the tip's radius plus a particle's: no centre nearer than this
};

struct InstrumentArgs {
  ParticleModel model;
  ParticleArrays arrays;
  ToolTip tip;
  std::uint32_t quota;            // aspirate: the most particles this step may take
  std::uint32_t first_live_slot;  // the live range, as ParticleArgs has it
  int live_count;
  std::uint64_t* candidates;        // aspirate: a key per candidate, capacity of them (scratch)
  std::uint32_t* candidate_count;   // ... and how many there are (0 between steps)
};

// A key that no candidate has: a particle out of reach, or no particle.
constexpr std::uint64_t kNoCandidate = ~std::uint64_t(0);

BLEEDSIM_HD inline int live_slot(const InstrumentArgs& a, int t) {
  return int((std::uint64_t(a.first_live_slot) + std::uint64_t(t)) % std::uint64_t(a.arrays.capacity));
}

// ---- aspirate ----------------------------------------------------------------------------------

// A non-negative float's bits order as the float does.
BLEEDSIM_HD inline std::uint32_t ordered_bits(float non_negative) {
  std::uint32_t bits;
  std::memcpy(&bits, &non_negative, sizeof bits);
  return bits;
}

// The slot's key when its particle lives within the suction's reach: (distance², slot), nearest
// first, ties by slot; kNoCandidate otherwise.
BLEEDSIM_HD inline std::uint64_t aspiration_key(const InstrumentArgs& a, int slot) {
  const ParticleArrays& p = a.arrays;
  if (!is_alive(a.model, p.age[slot])) return kNoCandidate;
  const float dx = p.position[2 * slot] - a.tip.x_mm, dy = p.position[2 * slot + 1] - a.tip.y_mm;
  const float d2 = dx * dx + dy * dy;
  if (!(d2 <= a.tip.reach_sq)) return kNoCandidate;
  return (std::uint64_t(ordered_bits(d2)) << 32) | std::uint32_t(slot);
}

BLEEDSIM_HD inline int slot_of_key(std::uint64_t key) { return int(key & 0xffffffffu); }

// The candidate's particle leaves by the suction (counted by the caller).
BLEEDSIM_HD inline void aspirate(const ParticleArrays& p, std::uint64_t key) {
  p.age[slot_of_key(key)] |= kAspirated;
}

// ---- contact -----------------------------------------------------------------------------------

// Whether (x, y) is outside the disc (centre c, radius r): the one test of "inside the tip".
BLEEDSIM_HD inline bool outside_disc(float x, float y, float cx, float cy, float r) {
  const float ex = x - cx, ey = y - cy;
  return ex * ex + ey * ey >= r * r;
}

struct Spot {
  float x, y;
};

// A point computed on the circle can round to an ulp inside it: it is stepped outward, one float
// at a time along the coordinates it may move in, until the test above says it is out.
BLEEDSIM_HD inline Spot step_out(Spot s, float cx, float cy, float r, bool move_x, bool move_y) {
  for (int i = 0; i < 64 && !outside_disc(s.x, s.y, cx, cy, r); ++i) {
    if (move_x) s.x = nextafterf(s.x, s.x >= cx ? 3.0e38f : -3.0e38f);
    if (move_y) s.y = nextafterf(s.y, s.y >= cy ? 3.0e38f : -3.0e38f);
  }
  return s;
}

// The point nearest to (x, y) that is neither inside the disc (centre c, radius r) nor outside the
// box [x0, x1] × [y0, y1]: its projection onto the circle when that is inside the box; else one
// of the circle's crossings of the box's edges or the box's corners outside the disc, the nearest
// (the first in this order on a tie). The box is wider and taller than the disc, so some corner is
// outside it.
BLEEDSIM_HD inline Spot nearest_outside_disc(float x, float y, float cx, float cy, float r, float x0, float x1,
                                              float y0, float y1) {
  const float dx = x - cx, dy = y - cy, d2 = dx * dx + dy * dy;
  if (d2 > 0.0f) {
    const float d = sqrtf(d2);
    const Spot on_circle = step_out({cx + r * (dx / d), cy + r * (dy / d)}, cx, cy, r, true, true);
    if (on_circle.x >= x0 && on_circle.x <= x1 && on_circle.y >= y0 && on_circle.y <= y1) return on_circle;
  }
  Spot best{x, y};
  float best_d2 = -1.0f;
  const auto consider = [&](Spot s) {
    if (s.x < x0 || s.x > x1 || s.y < y0 || s.y > y1 || !outside_disc(s.x, s.y, cx, cy, r)) return;
    const float fx = s.x - x, fy = s.y - y, f2 = fx * fx + fy * fy;
    if (best_d2 < 0.0f || f2 < best_d2) {
      best = s;
      best_d2 = f2;
    }
  };
  // Where the circle crosses the vertical edges x = x0, x1 and the horizontal ones y = y0, y1.
  for (int edge = 0; edge < 4; ++edge) {
    const bool vertical = edge < 2;
    const float at = edge == 0 ? x0 : edge == 1 ? x1 : edge == 2 ? y0 : y1;
    const float off = at - (vertical ? cx : cy), h2 = r * r - off * off;
    if (h2 < 0.0f) continue;
    const float h = sqrtf(h2), centre = vertical ? cy : cx;
    for (int side = 0; side < 2; ++side) {
      const float along = side == 0 ? centre - h : centre + h;
      consider(vertical ? step_out({at, along}, cx, cy, r, false, true) : step_out({along, at}, cx, cy, r, true, false));
    }
  }
  consider({x0, y0});
  consider({x1, y0});
  consider({x0, y1});
  consider({x1, y1});
  return best;
}

// A live particle whose centre is inside the tip's body is put on its edge (or the nearest free
// point of the panel), and its velocity relative to the tip loses its part along the body's
// normal into it: the blood parts around the tip and flows on along it. What it moves wakes.
BLEEDSIM_HD inline void keep_out_of_tip(const InstrumentArgs& a, int slot) {
  const ParticleArrays& p = a.arrays;
  const ParticleModel& m = a.model;
  if (!is_alive(m, p.age[slot])) return;
  const ToolTip& tip = a.tip;
  const float x = p.position[2 * slot], y = p.position[2 * slot + 1];
  if (outside_disc(x, y, tip.x_mm, tip.y_mm, tip.body_mm)) return;
  const Spot to = nearest_outside_disc(x, y, tip.x_mm, tip.y_mm, tip.body_mm, m.min_x, m.max_x, m.min_y, m.max_y);
  p.position[2 * slot] = to.x;
  p.position[2 * slot + 1] = to.y;
  p.rest[slot] = 0;  // moved: awake, its rest to begin here
  p.anchor[2 * slot] = to.x;
  p.anchor[2 * slot + 1] = to.y;
  // The normal at the new spot, out of the body; the velocity's approach along it is removed.
  const float nx0 = to.x - tip.x_mm, ny0 = to.y - tip.y_mm, n = sqrtf(nx0 * nx0 + ny0 * ny0);
  if (!(n > 0.0f)) return;
  const float nx = nx0 / n, ny = ny0 / n;
  const float vx = p.velocity[2 * slot], vy = p.velocity[2 * slot + 1];
  const float approach = (vx - tip.vx_mm_s) * nx + (vy - tip.vy_mm_s) * ny;
  if (approach < 0.0f) {
    p.velocity[2 * slot] = vx - approach * nx;
    p.velocity[2 * slot + 1] = vy - approach * ny;
  }
}

// The contact as a per-particle functor (core/physics/particle_kernels.h runs it).
struct KeepOutOfTip {
  InstrumentArgs a;
  BLEEDSIM_HD int count() const { return a.live_count; }
  BLEEDSIM_HD void operator()(int t) const { keep_out_of_tip(a, live_slot(a, t)); }
};

// The suction's twins, which InstrumentArgs selects: the quota's nearest candidates aspirated, over
// host memory (CPU reference) or device memory (CUDA).
void cpu_twin(const InstrumentArgs& suction, int threads);
void cuda_twin(const InstrumentArgs& suction);

}  // namespace bleedsim
