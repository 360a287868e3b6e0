#pragma once
// Particle blood flow (report §2.2.2): blood leaves a wound as particles, each a parcel of the film
// of blood on the mucosa. Gravity pulls it along the panel, viscous drag against the tissue slows
// it, neighbours push back when they touch (a contact stiff enough that the deepest pile stays
// incompressible to a stated tolerance) and pull together within a short range (surface tension),
// and the mucosa grips it: the film's edge is pinned and all of it has a yield stress, so small
// drops stay where they are and a pool comes to rest. It piles up at the bottom, then fades.
//
// One step, in the order a backend runs it (docs/particles.md has the model and its limits):
//   emit       new particles at the bleeding cuts, into the ring buffer (oldest overwritten)
//   bin        each live particle's grid cell; a stable sort of (cell, slot); each cell's range
//   collide    contact and cohesion from every neighbour in the 3 × 3 cells around, in fixed order
//   integrate  gravity, contacts and drag (semi-implicit Euler), the mucosa's grip, panel bounds, age
// Once per frame the splat stage (core/physics/splat.h) turns the live particles into a film of blood.
//
// On a tissue mesh (core/physics/surface.h) the same model runs in surface millimetres: velocities,
// forces and gravity are the surface's, in each texel's frame, positions the panel's; a texel off the
// surface is a wall.
//
// Every update reads the old state and writes a new one (collide reads sorted copies, integrate
// touches only its own slot), sums run in a fixed order, and there are no float atomics: the CPU
// reference and the CUDA kernels give the same bits.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "core/physics/counter_hash.h"
#include "core/physics/hd.h"
#include "core/physics/pixel_grid.h"
#include "core/physics/surface.h"
#include "core/physics/twin_cache.h"

namespace bleedsim {

// How long a particle lives, and over how many of its last steps it fades (made on the host by
// particle_lifetime(), core/effects/particles/particle_model.h). The splat needs only this of the model.
struct ParticleLifetime {
  std::uint32_t steps;
  std::uint32_t fade_steps;
};

// The model's constants for one run, as the floats both backends compute with (made once on
// the host by make_particle_model(), core/effects/particles/particle_model.h, which derives them).
struct ParticleModel {
  float radius_mm;
  float diameter_mm;
  float diameter_sq;       // diameter², the contact test
  float range_mm;          // the farthest a neighbour acts from: contact plus cohesion
  float range_sq;
  float band_inverse;      // 1/(range − diameter): the cohesion's fall beyond contact, a factor (0: no band)
  float stiffness;         // 1/s²: contact acceleration per mm of overlap (0: the film has depth)
  float pressure;          // mm/s²: the film with depth's push, this·q·(1 − q)³ at q = r/R (0: a contact)
  float kernel_inverse;    // 1/mm: 1/R, the film's kernel
  float parcel_depth;      // mm: a parcel's own depth at its centre, V·W(0) = 7V/(π·R²)
  float area_slope;        // 140·V/(π·R³): a parcel's area V/h times |∇W| is this·q·(1 − q)³/h
  float damping;           // 1/s: contact acceleration per mm/s of approach speed
  float cohesion;          // mm/s²: a neighbour's pull within the range
  float pinning;           // mm/s²: the grip on a particle of the film's edge (the contact)
  float yield;             // mm/s²: the grip on every particle (the contact)
  float yield_stress;      // mm²/s²: a film with depth's yield stress per unit density, τ_y/ρ ...
  float pinning_line;      // mm³/s²: ... and its contact line's pinning, a force per unit length per unit density
  float edge_openness;     // a particle whose neighbours' directions sum to more than this is on the edge
  float edge_company;      // ... and so is one with fewer neighbours than this (a drop of a few)
  float birth_steps;       // a pair with a particle this new has no force: its overlap is shifted away ...
                           // (a film with depth's: the longest a birth lasts) ...
  float birth_speed;       // mm/s: ... at no more than this
  float gravity_x;         // mm/s², along the panel (y points down); on a mesh, the surface's map says
  float gravity_y;
  float dt_s;              // one sub-step
  float drag_divisor;      // 1 + drag·dt: drag taken implicitly, so it never destabilises
  float max_speed;         // mm/s
  float max_speed_sq;
  float rest_distance_sq;  // mm²: a particle that stays this close to where it stopped is at rest ...
  std::uint32_t rest_steps;  // ... and asleep once at rest this many steps in a row (0: never)
  float wake_speed_sq;     // (mm/s)²: a neighbour faster than this within the range wakes a sleeper
  float min_x, max_x;      // where a centre touches a wall: the panel less one radius (in panel mm)
  float min_y, max_y;
  float wall_stiffness;    // 1/s²: a wall's push per mm a centre is past its line ...
  float wall_damping_divisor;  // ... and 1 + c_w·dt: its dashpot, critical and taken implicitly
  float wall_give;         // mm: the furthest past a wall's line a centre is let go, a backstop
  float cell_mm;           // grid cell edge in panel mm, ≥ the range on the surface
  int cells_x;
  int cells_y;
  ParticleLifetime lifetime;
  float jitter_mm;         // emission: position jitter, ± this in x and y
  float velocity_x;        // emission: initial velocity, mm/s ...
  float velocity_y;
  float velocity_jitter;   // ... ± this in x and y
  std::uint64_t seed;
  SurfaceMap surface;      // the tissue mesh's maps; empty on the flat panel
};

// What collide finds around a particle, for integrate: a neighbour within the range moves faster
// than the wake speed.
constexpr std::uint32_t kStirred = 2u;
// ... and, for a parcel of a film with depth being born, another birth nearer than kBirthsApart.
constexpr std::uint32_t kCrowded = 4u;

// A parcel of a film with depth is being born while its rest word holds this (docs/particles.md#births-
// of-a-film-with-depth): rest counts at most a lifetime's steps, below 2³¹, so it never reaches it.
constexpr std::uint32_t kBeingBorn = 0xffffffffu;
// ... until no other birth is nearer than this many diameters: the film it joins is then at most
// 1/0.99² − 1 = 2 % deeper than one layer at the births' spacing. (A whole diameter is reached only
// in the limit: the shift halves an overlap a step.)
constexpr float kBirthsApart = 0.99f;

// A slot whose age is at least the lifetime holds no particle; a slot never written holds this.
constexpr std::uint32_t kNeverUsed = 0xffffffffu;
// A particle the suction took (core/physics/instrument.h) keeps its slot, its age marked with this
// bit: it no longer lives, but it still ages in its slot, so that the accounting can tell when its
// id would have expired or been overwritten (lifetimes are below 2³¹ steps).
constexpr std::uint32_t kAspirated = 0x80000000u;

// What became of aspirated particles, counted where it happens (integer atomics, in any order):
// taken by the suction; and of those, the ones whose lifetime has since run out, and the ones
// whose slot a new particle has since taken while their lifetime ran.
struct AspiratedFates {
  std::uint64_t aspirated;
  std::uint64_t expired;
  std::uint64_t overwritten;
};

// The ring buffer (capacity slots; a particle with id n lives in slot n mod capacity) and the
// scratch a step needs. Positions and velocities are (x, y) pairs.
struct ParticleArrays {
  int capacity;
  float* position;           // mm
  float* velocity;           // mm/s
  std::uint32_t* age;        // steps lived
  std::uint32_t* rest;       // steps at rest in a row, up to the model's rest_steps: asleep there
  float* anchor;             // mm: where its rest began
  float* acceleration;       // contact acceleration, collide → integrate
  float* shift;              // mm: the move that undoes overlaps with new particles, collide → integrate
  float* grip;               // mm/s²: the mucosa's grip on it, collide → integrate
  std::uint32_t* neighbourhood;  // what collide found around it (kStirred), collide → integrate
  std::uint32_t* cell_key;   // the bin's keys: per slot (CPU); the t-th live slot's (CUDA)
  std::uint32_t* sorted_key;
  std::uint32_t* sorted_slot;
  float* sorted_position;
  float* sorted_velocity;
  std::uint32_t* sorted_birth;  // what collide needs of its birth: its age (the contact's births end by age),
                                // or its rest word (a film with depth's end by distance: kBeingBorn)
  float* sorted_depth;       // mm: a film with depth's depth at each sorted particle, bin → collide
  // cells + 1 entries: cell c's particles are sorted positions [cell_start[c], cell_start[c + 1]),
  // and cell_start[cells] is the number of living particles.
  std::uint32_t* cell_start;
  AspiratedFates* fates;      // one, for the whole ring
  void* sort_scratch;         // the CUDA bin's counts, places and scan storage (none on the CPU)
  std::size_t sort_scratch_bytes;
};

// One cut's new particles in one step: ids first_id … first_id + count − 1, which are new
// particles first_new … of this step.
struct Emitter {
  float x_mm;
  float y_mm;
  std::uint64_t first_id;
  std::uint32_t first_new;
  std::uint32_t count;
  float speed_scale = 1.0f;  // the emission velocity's multiple this step: a pulse's spurt, else 1
};

enum class ParticlePhase { emit, bin, collide, integrate };

struct ParticleArgs {
  ParticleModel model;
  ParticleArrays arrays;
  const Emitter* emitters;  // emit: sorted by first_new, their ids consecutive (new particle e: the first's first_id + e)
  int emitter_count;
  int new_count;            // emit: at most capacity
  std::uint64_t step;       // emit: the step number, for the jitter
  // The live particles, ids [oldest alive, emitted), fill live_count slots from first_live_slot
  // on, wrapping: every other slot is empty (aspirated particles are among them, no longer alive).
  // Loops over particles need visit only these. At emit, the range is the one before it.
  std::uint32_t first_live_slot;
  int live_count;
};

// ---- a frame's steps ---------------------------------------------------------------------------

// What changes from one step to the next, planned on the host from the cuts and the accounting
// alone, so that a backend can run many steps as one piece of work (CUDA: one graph a frame).
struct ParticleStep {
  std::uint64_t step;
  std::uint32_t first_emitter;  // its emitters: [first_emitter, + emitter_count) of the steps' list
  int emitter_count;
  int new_count;
  std::uint32_t emit_first_live_slot;  // the live range emission sees: the one before it
  int emit_live_count;
  std::uint32_t first_live_slot;  // the range bin, collide and integrate see
  int live_count;
};

// A run of consecutive steps. The step list and emitters are read from host memory; the CUDA twin
// copies them to device_steps and device_emitters (backend memory the caller allocated) and keeps
// the graph it launches in *cache, which lives as long as the caller's arrays do.
struct ParticleSteps {
  ParticleArgs base;  // the model and the arrays; what changes per step comes from steps
  const ParticleStep* steps;
  int count;
  const Emitter* emitters;
  int emitter_count;
  ParticleStep* device_steps;
  Emitter* device_emitters;
  std::unique_ptr<TwinCache>* cache;
};

// The arguments `phase` of `step` runs with: the live range before emission for emit, after it else.
BLEEDSIM_HD inline ParticleArgs args_at(ParticleArgs a, const ParticleStep& step, const Emitter* emitters,
                                        ParticlePhase phase) {
  const bool emitting = phase == ParticlePhase::emit;
  a.emitters = emitters + step.first_emitter;
  a.emitter_count = step.emitter_count;
  a.new_count = step.new_count;
  a.step = step.step;
  a.first_live_slot = emitting ? step.emit_first_live_slot : step.first_live_slot;
  a.live_count = emitting ? step.emit_live_count : step.live_count;
  return a;
}

BLEEDSIM_HD inline bool is_alive(const ParticleLifetime& l, std::uint32_t age) { return age < l.steps; }
BLEEDSIM_HD inline bool is_alive(const ParticleModel& m, std::uint32_t age) { return is_alive(m.lifetime, age); }
BLEEDSIM_HD inline bool is_aspirated(std::uint32_t age) { return (age & kAspirated) != 0 && age != kNeverUsed; }

// Whether the particles are parcels of a film with depth (further down), not discs in contact.
BLEEDSIM_HD inline bool has_depth(const ParticleModel& m) { return m.pressure > 0.0f; }

// Whether a parcel of a film with depth is still being born, from its rest word (or sorted_birth).
BLEEDSIM_HD inline bool being_born(const ParticleModel& m, std::uint32_t rest) {
  return has_depth(m) && rest == kBeingBorn;
}

// Adds one to a counter that many threads may add to: an integer, so the sum is the same in any order.
BLEEDSIM_HD inline void count_one(std::uint64_t* counter) {
#if defined(__CUDA_ARCH__)
  atomicAdd(reinterpret_cast<unsigned long long*>(counter), 1ull);
#else
  __atomic_fetch_add(counter, std::uint64_t(1), __ATOMIC_RELAXED);
#endif
}

// Whether slot lies in the live range [first_live_slot, + live_count), wrapping.
BLEEDSIM_HD inline bool in_live_range(std::uint32_t first_live_slot, int live_count, int capacity, std::size_t slot) {
  const std::uint64_t c = std::uint64_t(capacity);
  return (std::uint64_t(slot) + c - std::uint64_t(first_live_slot)) % c < std::uint64_t(live_count);
}

// The t-th live slot, t < live_count.
BLEEDSIM_HD inline int live_slot(const ParticleArgs& a, int t) {
  return int((std::uint64_t(a.first_live_slot) + std::uint64_t(t)) % std::uint64_t(a.arrays.capacity));
}

BLEEDSIM_HD inline float clamp_float(float v, float low, float high) {
  return min_float(max_float(v, low), high);
}

// ---- emit --------------------------------------------------------------------------------------

// A jittered position past a bound is mirrored back inside it, not clamped onto it: clamping would
// stack a cut's particles on the wall line, where contacts with each other point along the wall
// and nothing can push them off it.
BLEEDSIM_HD inline float reflect_inside(float v, float low, float high) {
  if (v < low) v = low + (low - v);
  if (v > high) v = high - (v - high);
  return clamp_float(v, low, high);
}

// The emitter of new particle t: the last whose first_new is at most t. A binary search: a stroke
// makes a cut a millimetre, and a thread that walked them in turn waited on a load for each.
BLEEDSIM_HD inline const Emitter& emitter_of(const ParticleArgs& a, std::uint32_t t) {
  int low = 0, high = a.emitter_count - 1;  // emitters[0].first_new is 0
  while (low < high) {
    const int middle = low + (high - low + 1) / 2;
    if (a.emitters[middle].first_new <= t) low = middle;
    else high = middle - 1;
  }
  return a.emitters[low];
}

// New particle t of this step: at its cut, jittered by the counter hash of (seed, id, step).
BLEEDSIM_HD inline void emit_particle(const ParticleArgs& a, int t) {
  const ParticleModel& m = a.model;
  const Emitter& from = emitter_of(a, std::uint32_t(t));
  const std::uint64_t id = from.first_id + (std::uint32_t(t) - from.first_new);
  const std::size_t slot = std::size_t(id % std::uint64_t(a.arrays.capacity));
  // A new particle takes the slot of the live one before it, overwriting it: counted here when that
  // one was aspirated, as the accounting has counted it overwritten (the live range is this step's,
  // before emission).
  if (in_live_range(a.first_live_slot, a.live_count, a.arrays.capacity, slot) && is_aspirated(a.arrays.age[slot]))
    count_one(&a.arrays.fates->overwritten);
  const auto jitter = [&](std::uint32_t stream) {
    return signed_unit(counter_hash(m.seed, id, a.step, stream));
  };
  float jx = m.jitter_mm * jitter(0), jy = m.jitter_mm * jitter(1);
  // On a mesh the jitter is on the surface; one that lands off it falls back to the cut.
  if (curved(m.surface)) to_panel(frame_at(m.surface, from.x_mm, from.y_mm), jx, jy, &jx, &jy);
  float x = reflect_inside(from.x_mm + jx, m.min_x, m.max_x), y = reflect_inside(from.y_mm + jy, m.min_y, m.max_y);
  if (curved(m.surface) && !on_surface(m.surface, x, y)) {
    x = clamp_float(from.x_mm, m.min_x, m.max_x);
    y = clamp_float(from.y_mm, m.min_y, m.max_y);
  }
  set_pair(a.arrays.position, slot, {x, y});
  set_pair(a.arrays.velocity, slot,
           {m.velocity_x * from.speed_scale + m.velocity_jitter * jitter(2),
            m.velocity_y * from.speed_scale + m.velocity_jitter * jitter(3)});
  a.arrays.age[slot] = 0;
  a.arrays.rest[slot] = has_depth(m) ? kBeingBorn : 0u;
  set_pair(a.arrays.anchor, slot, {x, y});
}

// Which of this step's new particles a slot receives (new_count: none). Their ids run on from the
// first emitter's first_id, so new particle e goes to slot (first id + e) mod capacity: a backend
// may emit each new particle from the thread that owns its slot.
BLEEDSIM_HD inline int new_particle_in(const ParticleArgs& a, std::size_t slot) {
  if (a.new_count == 0) return 0;
  const std::uint64_t capacity = std::uint64_t(a.arrays.capacity);
  const std::uint64_t e = (std::uint64_t(slot) + capacity - a.emitters[0].first_id % capacity) % capacity;
  return e < std::uint64_t(a.new_count) ? int(e) : a.new_count;
}

// ---- bin ---------------------------------------------------------------------------------------

BLEEDSIM_HD inline std::uint32_t cell_count(const ParticleModel& m) {
  return std::uint32_t(m.cells_x) * std::uint32_t(m.cells_y);
}

// One past the last cell.
BLEEDSIM_HD inline std::uint32_t sentinel_key(const ParticleModel& m) { return cell_count(m); }

// Clamped before the conversion: float→int of out-of-range values differs between CPU and GPU.
BLEEDSIM_HD inline int cell_coordinate(float v_mm, float cell_mm, int cells) {
  return static_cast<int>(clamp_float(floorf(v_mm / cell_mm), 0.0f, static_cast<float>(cells - 1)));
}

BLEEDSIM_HD inline std::uint32_t cell_key_of(const ParticleArrays& p, const ParticleModel& m, int slot) {
  if (!is_alive(m, p.age[slot])) return sentinel_key(m);
  const FloatPair at = pair_at(p.position, std::size_t(slot));
  const int cx = cell_coordinate(at.x, m.cell_mm, m.cells_x);
  const int cy = cell_coordinate(at.y, m.cell_mm, m.cells_y);
  return std::uint32_t(cy) * std::uint32_t(m.cells_x) + std::uint32_t(cx);
}

// The n-th live slot in ascending slot order, n < live_count (the live range wraps round the ring):
// the order the bin takes them in, and so the order it keeps within a cell.
BLEEDSIM_HD inline int nth_live_slot_ascending(const ParticleArgs& a, int n) {
  const int past_end = int(a.first_live_slot) + a.live_count - a.arrays.capacity;
  const int wrapped = past_end > 0 ? past_end : 0;
  return n < wrapped ? n : int(a.first_live_slot) + (n - wrapped);
}

// The sorted copies collide reads, so no thread reads a slot another thread is writing.
BLEEDSIM_HD inline void gather_sorted(const ParticleArrays& p, const ParticleModel& m, int i) {
  const std::uint32_t slot = p.sorted_slot[i];
  set_pair(p.sorted_position, std::size_t(i), pair_at(p.position, slot));
  set_pair(p.sorted_velocity, std::size_t(i), pair_at(p.velocity, slot));
  p.sorted_birth[i] = has_depth(m) ? p.rest[slot] : p.age[slot];
}

// ---- collide -----------------------------------------------------------------------------------

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
  float cx = 0.0f, cy = 0.0f;  // 1/mm: ... and the gradient of its colour, Σ (V/h_j)·∇W: the edge's
  float hx = 0.0f, hy = 0.0f;  // mm: half of each overlap with a new particle, away from it
  bool crowded = false;        // a pair still parting overlaps it
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
// (collide_particle): two parcels being born part, two born ones push with their whole force.
// Returns the share of its force a pair has, or −1 while it parts.
BLEEDSIM_HD inline float pair_growth(const ParticleModel& m, std::uint32_t birth, std::uint32_t other_birth) {
  if (has_depth(m)) return being_born(m, birth) ? -1.0f : 1.0f;
  const float younger = float(birth < other_birth ? birth : other_birth), half_birth = 0.5f * m.birth_steps;
  if (younger < half_birth) return -1.0f;
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
  if (growth < 0.0f) {
    const float half_overlap = 0.5f * max_float(m.diameter_mm - r, 0.0f);
    sums->hx += half_overlap * nx;
    sums->hy += half_overlap * ny;
    sums->crowded = sums->crowded || r < kBirthsApart * m.diameter_mm;
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
// area V/h bears the yield stress, and its share of the line, (V/h)·|∇c| (which sums to the
// film's perimeter, c the film's colour), the pinning; per unit mass, (τ_y/ρ + q_p·|∇c|)/h.
BLEEDSIM_HD inline float grip_from(const ParticleModel& m, const PairSums& sums) {
  if (has_depth(m))
    return (m.yield_stress + m.pinning_line * sqrtf(sums.cx * sums.cx + sums.cy * sums.cy)) / sums.depth;
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

// The edge's part of the film with depth's pair: the colour's gradient, toward the neighbour at
// offset (dx, dy), of depth h_j: (V/h_j)·|∇W|.
BLEEDSIM_HD inline void add_colour(const ParticleModel& m, float dx, float dy, float r, float other_depth,
                                   PairSums* sums) {
  const float toward = m.area_slope * kernel_slope(m, r) / (other_depth * r);
  sums->cx -= toward * dx;
  sums->cy -= toward * dy;
}

// An image of a parcel of depth `depth` pushes and colours as the parcel would.
BLEEDSIM_HD inline void add_wall_images(const ParticleModel& m, float px, float py, float qx, float qy, float depth,
                                        PairSums* sums) {
  for_each_wall_image(m, px, py, qx, qy, [&](float dx, float dy, float r2) {
    const float r = sqrtf(r2), push = film_push(m, r) / r;
    sums->ax += push * dx;
    sums->ay += push * dy;
    add_colour(m, dx, dy, r, depth, sums);
  });
}

// The sorted positions [begin, end) of the particles in cells x0 … x1 of row y: the cells of a row
// are consecutive keys, so their particles are one run of the sorted order.
struct SortedRun {
  std::uint32_t begin, end;
};
BLEEDSIM_HD inline SortedRun row_run(const ParticleArrays& p, const ParticleModel& m, int y, int x0, int x1) {
  const std::uint32_t row = std::uint32_t(y) * std::uint32_t(m.cells_x);
  return {p.cell_start[row + std::uint32_t(x0)], p.cell_start[row + std::uint32_t(x1) + 1]};
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
// with this one (the slot names the pair's direction only then). A film with depth adds its edge's
// colour and the walls' images. A parcel being born is in the film's depth and pushes the film as
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
    if (!in_film) return;
    const float other_depth = p.sorted_depth[j];
    if (r2 > 0.0f) add_colour(m, dx, dy, sqrtf(r2), other_depth, &sums);
    add_wall_images(m, px, py, qx, qy, other_depth, &sums);
  });
  if (in_film) add_wall_images(m, px, py, px, py, sums.depth, &sums);
  finish_pair_sums(p, m, slot, sums);
}

// ---- integrate ---------------------------------------------------------------------------------

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
  return m.rest_steps > 0 && rest >= m.rest_steps && !being_born(m, rest);
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
BLEEDSIM_HD inline std::uint32_t rest_after(const ParticleModel& m, std::uint32_t rest, FloatPair moved) {
  if (moved.x * moved.x + moved.y * moved.y > m.rest_distance_sq) return 0;
  return rest < m.rest_steps ? rest + 1 : m.rest_steps;
}

// A parcel of a film with depth being born (docs/particles.md#births-of-a-film-with-depth) moves by
// its shift alone, inside the panel. It keeps the velocity it was emitted with for when it joins
// the film, slowed by the drag as a lone particle's would be (a burst's jitter is spent while it
// parts, a jet's kept by a birth of one step): once no other birth is nearer than kBirthsApart,
// or at birth_steps all the same (a birth that has found no room by then joins where it is). It joins
// where it stands, its rest beginning there.
BLEEDSIM_HD inline void step_birth(const ParticleArrays& p, const ParticleModel& m, int slot, std::uint32_t age) {
  const FloatPair at = pair_at(p.position, std::size_t(slot)), shift = pair_at(p.shift, std::size_t(slot));
  const float x = clamp_float(at.x + shift.x, m.min_x, m.max_x), y = clamp_float(at.y + shift.y, m.min_y, m.max_y);
  const FloatPair v = pair_at(p.velocity, std::size_t(slot));
  set_pair(p.position, std::size_t(slot), {x, y});
  set_pair(p.velocity, std::size_t(slot), {v.x / m.drag_divisor, v.y / m.drag_divisor});
  p.age[slot] = age + 1;
  const bool crowded = (p.neighbourhood[slot] & kCrowded) != 0u && float(age + 1) < m.birth_steps;
  p.rest[slot] = crowded ? kBeingBorn : 0u;
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

// ---- fade --------------------------------------------------------------------------------------

// How much of a particle is still there over its last fade_steps: from 1 down to 1/fade_steps,
// never 0 while it lives, so it fades out instead of popping.
BLEEDSIM_HD inline float fade_alpha(const ParticleLifetime& l, std::uint32_t age) {
  return min_float(1.0f, float(l.steps - age) / float(l.fade_steps));
}

// The twins: one phase of a step over host memory (CPU reference) or device memory (CUDA).
void cpu_twin(ParticlePhase phase, const ParticleArgs& args, int threads);
void cuda_twin(ParticlePhase phase, const ParticleArgs& args);
// Every phase of every step of a run, in order.
void cpu_twin(const ParticleSteps& steps, int threads);
void cuda_twin(const ParticleSteps& steps);
// Bytes of temporary storage the CUDA bin needs for `capacity` particles in `cells` cells.
std::size_t particle_sort_scratch_cuda(int capacity, std::uint32_t cells);

}  // namespace bleedsim
