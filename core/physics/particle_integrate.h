#pragma once
// Integrate (core/physics/particles.h): gravity, the pairs' forces and drag, the mucosa's grip,
// the walls, rest and age, each particle from its own slot.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/physics/hd.h"
#include "core/physics/particle_state.h"
#include "core/physics/pixel_grid.h"
#include "core/physics/surface.h"

namespace bleedsim {

// An aspirated particle ages in its slot, and is counted when its lifetime runs out, as the
// accounting counts its id expired then. Of the rest of a step only emission, which may give the
// slot a new particle, touches a dead slot: a backend may age it at any point after that (CUDA:
// in the bin's first launch, from the thread that would have emitted into it).
BLEEDSIM_HD inline void age_aspirated(const ParticleArrays& p, const ParticleModel& m, int slot) {
  const std::uint32_t age = p.age[slot];
  if (!is_aspirated(age)) return;
  p.age[slot] = age + 1;
  if (((age + 1) & ~kAspirated) == m.lifetime.steps) count_one(&p.fates->expired);
}

// The panel's edges are walls with the contact's spring (docs/particles.md#walls), not a clamp: a
// centre past a wall's line (where its particle touches the wall) by δ is pushed back by
// wall_stiffness·δ. A clamp held a pile's bottom row exactly on the line, where the pile's weight
// squeezed it along the wall. The wall's dashpot is critical and taken implicitly, like the drag
// (wall_damped): at the pair's ζ = 0.1 blood met a wall with a restitution of 0.73, and blood does
// not bounce; explicitly, a critical dashpot would break the step's damping limit.
BLEEDSIM_HD inline float wall_push(const ParticleModel& m, float past) {
  return past > 0.0f ? m.wall_stiffness * past : 0.0f;
}

// The four walls' springs on a centre at (x, y), in panel mm.
BLEEDSIM_HD inline FloatPair wall_acceleration(const ParticleModel& m, float x, float y) {
  return {wall_push(m, m.min_x - x) - wall_push(m, x - m.max_x), wall_push(m, m.min_y - y) - wall_push(m, y - m.max_y)};
}

// A velocity (the surface's, in `frame`) with the dashpots of the walls a centre at (x, y) is past,
// along each wall's normal.
BLEEDSIM_HD inline void wall_damped(const ParticleModel& m, const SurfaceFrame& frame, float x, float y, float* vx,
                                    float* vy) {
  const bool on_x_wall = x < m.min_x || x > m.max_x, on_y_wall = y < m.min_y || y > m.max_y;
  if (!on_x_wall && !on_y_wall) return;
  float px = *vx, py = *vy;
  if (curved(m.surface)) to_panel(frame, *vx, *vy, &px, &py);
  if (on_x_wall) px /= m.wall_damping_divisor;
  if (on_y_wall) py /= m.wall_damping_divisor;
  if (curved(m.surface)) to_surface(frame, px, py, vx, vy);
  else *vx = px, *vy = py;
}

// Blood that has stopped sleeps (docs/particles.md#rest). A particle that has stayed within
// rest_distance of one spot for the model's rest_steps in a row is asleep: it stays where it is, at
// no speed, until something moves around it: a neighbour within the range faster than the wake
// speed, a new particle overlapping it (its shift), the tip (which wakes what it moves), or a force
// past twice its grip (a neighbour taken away by suction or by its lifetime, gravity turned). A
// sleeper's own force does not wake it short of that: frozen among frozen neighbours it is the
// same every step, and freezing a creeping particle changes its dashpots' pull by the damping
// times its creep. Without sleep, static friction held every particle whose force it balanced, but
// a pile whose particles crept below any visible speed rearranged itself until it avalanched,
// seconds after it had stopped. Rest is a distance, not a speed: a pile at rest rings at the
// contact's frequency with nanometres of amplitude, which a speed test of each step sees.
BLEEDSIM_HD inline bool asleep(const ParticleModel& m, std::uint32_t rest) {
  return m.rest_steps > 0 && rest >= m.rest_steps && !being_born(m, rest) && !joining(m, rest);
}

// The grip as the step takes it is grip·(1 + γ·dt): a particle held by its grip is within it.
BLEEDSIM_HD inline bool stays_asleep(const ParticleModel& m, float fx, float fy, std::uint32_t neighbourhood,
                                     float grip, FloatPair shift) {
  const float most = 2.0f * grip * m.drag_divisor;
  return (neighbourhood & kStirred) == 0u && fx * fx + fy * fy <= most * most && shift.x == 0.0f &&
         shift.y == 0.0f;
}

// Steps at rest in a row after a step that ended `moved` from the anchor: counted up to
// rest_steps, or 0 when it has left the anchor (which then moves to where it is).
// A parcel joining the film counts its steps since instead, and begins its rest once it has joined.
BLEEDSIM_HD inline std::uint32_t rest_after(const ParticleModel& m, std::uint32_t rest, FloatPair moved) {
  if (joining(m, rest)) return float(rest + 1u - kJoining) >= m.join_steps ? 0u : rest + 1u;
  if (moved.x * moved.x + moved.y * moved.y > m.rest_distance_sq) return 0;
  return rest < m.rest_steps ? rest + 1 : m.rest_steps;
}

// A parcel of a film with depth being born (docs/particles.md#births-of-a-film-with-depth) moves by
// its shift alone, inside the panel. It keeps the velocity it was emitted with for when it joins
// the film, slowed by the drag as a lone particle's would be (a burst's jitter is spent while it
// parts, a jet's kept by a birth of one step): once no other birth is nearer than kBirthsApart, its
// rest beginning where it stands; or, at birth_steps all the same, joining (kJoining) where it is.
BLEEDSIM_HD inline void step_birth(const ParticleArrays& p, const ParticleModel& m, int slot, std::uint32_t age) {
  const FloatPair at = pair_at(p.position, std::size_t(slot)), shift = pair_at(p.shift, std::size_t(slot));
  const float x = clamp_float(at.x + shift.x, m.min_x, m.max_x), y = clamp_float(at.y + shift.y, m.min_y, m.max_y);
  const FloatPair v = pair_at(p.velocity, std::size_t(slot));
  set_pair(p.position, std::size_t(slot), {x, y});
  set_pair(p.velocity, std::size_t(slot), {v.x / m.drag_divisor, v.y / m.drag_divisor});
  p.age[slot] = age + 1;
  const bool crowded = (p.neighbourhood[slot] & kCrowded) != 0u;
  p.rest[slot] = !crowded ? 0u : float(age + 1) < m.birth_steps ? kBeingBorn : kJoining;
  if (!crowded) set_pair(p.anchor, std::size_t(slot), {x, y});
}

// Semi-implicit Euler: the new velocity from gravity, contacts and the walls, drag and the walls'
// dashpots taken implicitly;
// then the grip as friction taken implicitly (Coulomb): it removes up to grip·dt of the speed, and
// holds a particle it can stop, so the film comes to rest instead of creeping; then capped at the
// speed limit. The new position from the new velocity, and the shift away from new particles; the
// backstop, wall_give past a wall's line, stops a particle there. On a mesh, gravity is the
// surface's at the particle's texel, the walls' push is taken into that texel's frame and the move
// back to the panel through it, and a move off the surface is not made: the particle stops where
// it was.
// A sleeper that stays asleep only ages; one that falls asleep stops.
BLEEDSIM_HD inline void integrate_particle(const ParticleArrays& p, const ParticleModel& m, int slot) {
  const std::uint32_t age = p.age[slot];
  if (!is_alive(m, age)) {
    age_aspirated(p, m, slot);
    return;
  }
  if (being_born(m, p.rest[slot])) {
    step_birth(p, m, slot, age);
    return;
  }
  const auto [x0, y0] = pair_at(p.position, std::size_t(slot));
  float gx = m.gravity_x, gy = m.gravity_y;
  SurfaceFrame frame{1.0f, 0.0f, 1.0f};
  if (curved(m.surface)) {
    const std::size_t texel = pixel_containing(m.surface.grid, x0, y0);
    frame = frame_of(m.surface, texel);
    gx = m.surface.gravity[kSurfaceGravityChannels * texel];
    gy = m.surface.gravity[kSurfaceGravityChannels * texel + 1];
  }
  const FloatPair v0 = pair_at(p.velocity, std::size_t(slot)), a = pair_at(p.acceleration, std::size_t(slot));
  FloatPair wall = wall_acceleration(m, x0, y0);
  if (curved(m.surface)) to_surface(frame, wall.x, wall.y, &wall.x, &wall.y);
  const float fx = gx + a.x + wall.x, fy = gy + a.y + wall.y;
  const FloatPair shift = pair_at(p.shift, std::size_t(slot));
  const std::uint32_t neighbourhood = p.neighbourhood[slot];
  const std::uint32_t rest = p.rest[slot];
  const float grip = p.grip[slot];
  if (asleep(m, rest) && stays_asleep(m, fx, fy, neighbourhood, grip, shift)) {
    p.age[slot] = age + 1;
    return;
  }
  float vx = (v0.x + m.dt_s * fx) / m.drag_divisor;
  float vy = (v0.y + m.dt_s * fy) / m.drag_divisor;
  wall_damped(m, frame, x0, y0, &vx, &vy);
  const float speed_sq = vx * vx + vy * vy;
  const float held = grip * m.dt_s;
  if (speed_sq <= held * held) {
    vx = 0.0f;
    vy = 0.0f;
  } else {
    const float speed = sqrtf(speed_sq);
    const float kept = min_float(speed - held, m.max_speed) / speed;
    vx *= kept;
    vy *= kept;
  }
  float mx = vx, my = vy, sx = shift.x, sy = shift.y;
  if (curved(m.surface)) {
    to_panel(frame, vx, vy, &mx, &my);
    to_panel(frame, sx, sy, &sx, &sy);
  }
  float x = x0 + m.dt_s * mx + sx;
  float y = y0 + m.dt_s * my + sy;
  if (x < m.min_x - m.wall_give) { x = m.min_x - m.wall_give; vx = max_float(vx, 0.0f); }
  if (x > m.max_x + m.wall_give) { x = m.max_x + m.wall_give; vx = min_float(vx, 0.0f); }
  if (y < m.min_y - m.wall_give) { y = m.min_y - m.wall_give; vy = max_float(vy, 0.0f); }
  if (y > m.max_y + m.wall_give) { y = m.max_y + m.wall_give; vy = min_float(vy, 0.0f); }
  if (curved(m.surface) && !on_surface(m.surface, x, y)) {
    x = x0;
    y = y0;
    vx = 0.0f;
    vy = 0.0f;
  }
  // Awake from here on: a sleeper that woke starts counting again.
  const FloatPair anchor = pair_at(p.anchor, std::size_t(slot));
  const std::uint32_t rest_now = rest_after(m, asleep(m, rest) ? 0 : rest, {x - anchor.x, y - anchor.y});
  if (rest_now == 0) set_pair(p.anchor, std::size_t(slot), {x, y});
  if (asleep(m, rest_now)) {
    vx = 0.0f;
    vy = 0.0f;
  }
  set_pair(p.position, std::size_t(slot), {x, y});
  set_pair(p.velocity, std::size_t(slot), {vx, vy});
  p.age[slot] = age + 1;
  p.rest[slot] = rest_now;
}

}  // namespace bleedsim
