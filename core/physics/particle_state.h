#pragma once
// The particle blood flow's state (core/physics/particles.h has the model and its phases): the
// model's constants, the ring buffer and its scratch, a step's arguments, and what every phase asks
// of a slot.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "core/physics/hd.h"
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
  float damping;           // 1/s: contact acceleration per mm/s of approach speed
  float cohesion;          // mm/s²: a neighbour's pull within the range
  float pinning;           // mm/s²: the grip on a particle of the film's edge (the contact)
  float yield;             // mm/s²: the grip on every particle (the contact)
  float yield_stress;      // mm²/s²: a film with depth's yield stress per unit density, τ_y/ρ ...
  float line_grip;         // 1/s²: ... and its contact line's pinning per parcel, q_p/V: the grip per mm of
                           // a parcel's share of the line (core/physics/particle_line.h) ...
  int line_nodes_x;        // ... measured on a grid of this many nodes a row ...
  int line_nodes_y;        // ... and a column ...
  float line_step_x;       // mm: ... this far apart (line_grid_mm, fitted to the panel) ...
  float line_step_y;
  float wetted_weight;     // ... each of which is wet once its parcels' weights sum to this
  float edge_openness;     // a particle whose neighbours' directions sum to more than this is on the edge
  float edge_company;      // ... and so is one with fewer neighbours than this (a drop of a few)
  float birth_steps;       // a pair with a particle this new has no force: its overlap is shifted away ...
                           // (a film with depth's: the longest a birth lasts) ...
  float birth_speed;       // mm/s: ... at no more than this
  float join_steps;        // a film with depth's birth that ran out crowded grows into its push over these
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
// ... or, crowded still when birth_steps run out, joins gradually: its rest word then counts the steps
// since from this up, and its pairs grow into their push over join_steps, so that a crowd that found
// no room (a burst of 12,000) is not released at once into the push of a film many layers deep.
constexpr std::uint32_t kJoining = 0x80000000u;

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
  float* line_weight;        // a film with depth's parcels' weights on each node of its contact line's grid,
                             // bin → collide
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

// Whether the particles are parcels of a film with depth (docs/particles.md#a-film-with-depth), not
// discs in contact.
BLEEDSIM_HD inline bool has_depth(const ParticleModel& m) { return m.pressure > 0.0f; }

// Whether a parcel of a film with depth is still being born, from its rest word (or sorted_birth) ...
BLEEDSIM_HD inline bool being_born(const ParticleModel& m, std::uint32_t rest) {
  return has_depth(m) && rest == kBeingBorn;
}

// ... or joining the film after its birth ran out crowded.
BLEEDSIM_HD inline bool joining(const ParticleModel& m, std::uint32_t rest) {
  return has_depth(m) && rest >= kJoining && rest != kBeingBorn;
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

// How much of a particle is still there over its last fade_steps: from 1 down to 1/fade_steps,
// never 0 while it lives, so it fades out instead of popping.
BLEEDSIM_HD inline float fade_alpha(const ParticleLifetime& l, std::uint32_t age) {
  return min_float(1.0f, float(l.steps - age) / float(l.fade_steps));
}

}  // namespace bleedsim
