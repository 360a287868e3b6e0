// The particle model's parts, each against something that does not share its code: the accounting
// against a slot-by-slot replay of the ring buffer, pair forces against Newton's third law and
// their formulas, the stability limit against a pile run just inside and just outside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <vector>

#include "core/effects/particles/particle_accounting.h"
#include "core/effects/particles/particle_buffers.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/physics/particles.h"
#include "core/runtime/backend.h"
#include "tests/effects/particle_box.h"

namespace bleedsim {
namespace {

// ---- accounting --------------------------------------------------------------------------------

// The ring buffer replayed slot by slot: who lives where, and what happened to everyone else.
struct RingReplay {
  std::uint64_t capacity, lifetime;
  std::vector<std::int64_t> id_in_slot;  // −1: empty
  std::map<std::int64_t, std::uint64_t> born;
  std::uint64_t next_id = 0, expired = 0, overwritten = 0;

  RingReplay(std::uint64_t c, std::uint64_t l) : capacity(c), lifetime(l), id_in_slot(c, -1) {}

  void step(std::uint64_t step, std::uint64_t count) {
    for (std::uint64_t k = 0; k < count; ++k, ++next_id) {
      std::int64_t& occupant = id_in_slot[next_id % capacity];
      if (occupant >= 0) ++overwritten;
      occupant = std::int64_t(next_id);
      born[occupant] = step;
    }
    for (std::int64_t& occupant : id_in_slot)
      if (occupant >= 0 && step + 1 - born[occupant] >= lifetime) ++expired, occupant = -1;
  }
  std::uint64_t alive() const {
    std::uint64_t n = 0;
    for (std::int64_t occupant : id_in_slot) n += occupant >= 0;
    return n;
  }
};

void expect_accounting_matches_replay(std::uint64_t capacity, std::uint64_t lifetime,
                                      const std::vector<std::uint64_t>& emitted_per_step) {
  ParticleAccounting accounting(capacity, lifetime);
  RingReplay replay(capacity, lifetime);
  for (std::uint64_t s = 0; s < emitted_per_step.size(); ++s) {
    accounting.emit(s, emitted_per_step[s]);
    accounting.end_step(s);
    replay.step(s, emitted_per_step[s]);
    const ParticleCounts c = accounting.counts();
    ASSERT_EQ(c.emitted, replay.next_id) << "step " << s;
    ASSERT_EQ(c.alive, replay.alive()) << "step " << s;
    ASSERT_EQ(c.expired, replay.expired) << "step " << s;
    ASSERT_EQ(c.overwritten, replay.overwritten) << "step " << s;
    ASSERT_EQ(c.emitted, c.alive + c.expired + c.overwritten) << "step " << s;
  }
}

TEST(ParticleAccounting, ExpiryAloneMatchesTheRingReplayed) {
  expect_accounting_matches_replay(100, 7, {3, 0, 5, 1, 0, 0, 0, 0, 2, 9, 0, 0, 0, 0, 0, 0, 0, 4});
}

TEST(ParticleAccounting, OverwritingAloneMatchesTheRingReplayed) {
  expect_accounting_matches_replay(8, 1000, std::vector<std::uint64_t>(40, 3));
}

TEST(ParticleAccounting, MoreThanARingInOneStepIsOverwrittenAtOnce) {
  expect_accounting_matches_replay(5, 1000, {2, 13, 0, 1, 7});
}

TEST(ParticleAccounting, ExpiryAndOverwritingTogetherMatchTheRingReplayed) {
  // Bursts that wrap the ring of 16 while particles live 6 steps: both fates, in every order.
  std::vector<std::uint64_t> counts;
  for (int s = 0; s < 200; ++s) counts.push_back(std::uint64_t((s * 7919) % 11 == 0 ? 20 : (s * 31) % 5));
  expect_accounting_matches_replay(16, 6, counts);
}

// ---- the model's parts -------------------------------------------------------------------------

// What the splat and the memory estimate take instead of the whole model is the model's own.
TEST(ParticleModel, ItsPartsAreTheWholeModels) {
  Scene scene;
  scene.domain = Domain{200, 150, 47.3, 31.9};  // not whole cells
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().cell_mm = 0.45;
  scene.effects.get<ParticleParams>().lifetime_s = 2.0;
  scene.effects.get<ParticleParams>().fade_s = 0.3;
  scene.effects.get<ParticleParams>().substeps = 400;
  const ParticleModel m = resolve_particles(scene).model;
  EXPECT_EQ(resolve_particles(scene).lifetime.steps, m.lifetime.steps);
  EXPECT_EQ(resolve_particles(scene).lifetime.fade_steps, m.lifetime.fade_steps);
  EXPECT_EQ(m.lifetime.steps, 24000u);  // 2 s at 30 Hz × 400 sub-steps
  EXPECT_EQ(resolve_particles(scene).cells, Count(cell_count(m)));
  EXPECT_EQ(cell_count(m), 106u * 71u);  // ⌈47.3 / 0.45⌉ × ⌈31.9 / 0.45⌉
}

// ---- random numbers ----------------------------------------------------------------------------

TEST(CounterHash, DependsOnEveryCounterAndIsEvenlySpread) {
  EXPECT_EQ(counter_hash(1, 2, 3, 4), counter_hash(1, 2, 3, 4));
  EXPECT_NE(counter_hash(1, 2, 3, 4), counter_hash(2, 2, 3, 4));
  EXPECT_NE(counter_hash(1, 2, 3, 4), counter_hash(1, 3, 3, 4));
  EXPECT_NE(counter_hash(1, 2, 3, 4), counter_hash(1, 2, 4, 4));
  EXPECT_NE(counter_hash(1, 2, 3, 4), counter_hash(1, 2, 3, 5));
  EXPECT_NE(counter_hash(0, std::uint64_t(1) << 32, 0, 0), counter_hash(0, 0, 0, 0));  // high id bits count
  double sum = 0.0, low = 1.0, high = -1.0;
  const int n = 100000;
  for (int id = 0; id < n; ++id) {
    const float u = signed_unit(counter_hash(7, std::uint64_t(id), 0, 0));
    sum += u;
    low = std::min(low, double(u));
    high = std::max(high, double(u));
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);  // uniform on [−1, 1): mean 0, standard error 0.0018
  EXPECT_GE(low, -1.0);
  EXPECT_LT(high, 1.0);
  EXPECT_LT(low, -0.999);
  EXPECT_GT(high, 0.999);
}

// ---- the host's fminf and fmaxf ----------------------------------------------------------------

// min_float and max_float (core/physics/hd.h) against libm, over every pairing of signed zeros,
// ones, a subnormal, infinities and NaNs: libm's bits wherever C fixes the result (two numbers, or a
// NaN and a number); where it does not, y for +0 against −0 and x for two NaNs (both allowed).
TEST(HostMinMax, GiveLibmsResultsWhereCFixesThem) {
  const auto bits = [](float v) {
    std::uint32_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::vector<float> values = {0.0f, -0.0f, 1.0f, -1.0f, 2.5e-39f, inf, -inf, nan, -nan};
  for (const float x : values)
    for (const float y : values) {
      if (x == 0.0f && y == 0.0f && std::signbit(x) != std::signbit(y)) {
        EXPECT_EQ(bits(max_float(x, y)), bits(y)) << x << ", " << y;
        EXPECT_EQ(bits(min_float(x, y)), bits(y)) << x << ", " << y;
        continue;
      }
      if (std::isnan(x) && std::isnan(y)) {
        EXPECT_EQ(bits(max_float(x, y)), bits(x)) << x << ", " << y;
        EXPECT_EQ(bits(min_float(x, y)), bits(x)) << x << ", " << y;
        continue;
      }
      // volatile: the library's functions, not the compiler's folding of them.
      volatile float vx = x, vy = y;
      EXPECT_EQ(bits(max_float(x, y)), bits(std::fmax(float(vx), float(vy)))) << x << ", " << y;
      EXPECT_EQ(bits(min_float(x, y)), bits(std::fmin(float(vx), float(vy)))) << x << ", " << y;
    }
}

// ---- pair forces -------------------------------------------------------------------------------

// The default contact, with cohesion, for a scene of any panel.
ParticleModel pair_model() {
  Scene scene = test::box_scene(16, 12);
  return resolve_particles(scene).model;
}

// ---- emit --------------------------------------------------------------------------------------

// Every new particle leaves from its own cut: for one cut and for many, of one to five particles
// each, the particles of a cut's range of new ones [first_new, first_new + count) are written to
// their ids' slots at that cut (no jitter), the cut found here by walking the cuts in turn.
TEST(ParticleEmit, EachNewParticleLeavesFromItsOwnCut) {
  ParticleModel m = pair_model();
  m.jitter_mm = 0.0f;
  m.velocity_jitter = 0.0f;
  constexpr int kCapacity = 2048;
  std::vector<float> position(2 * kCapacity), velocity(2 * kCapacity), anchor(2 * kCapacity);
  std::vector<std::uint32_t> age(kCapacity, kNeverUsed), rest(kCapacity, 7u);
  ParticleArgs a{};
  a.model = m;
  a.arrays.capacity = kCapacity;
  a.arrays.position = position.data();
  a.arrays.velocity = velocity.data();
  a.arrays.age = age.data();
  a.arrays.rest = rest.data();
  a.arrays.anchor = anchor.data();
  for (const int cuts : {1, 2, 3, 64, 257}) {
    std::vector<Emitter> emitters;
    std::uint32_t first_new = 0;
    for (int c = 0; c < cuts; ++c) {
      const std::uint32_t count = 1 + std::uint32_t(c * 7 % 5);
      emitters.push_back({0.5f + 0.05f * float(c), 1.0f + 0.03f * float(c), 1000 + first_new, first_new, count});
      first_new += count;
    }
    a.emitters = emitters.data();
    a.emitter_count = cuts;
    a.new_count = int(first_new);
    for (int t = 0; t < a.new_count; ++t) emit_particle(a, t);
    for (const Emitter& cut : emitters)
      for (std::uint32_t k = 0; k < cut.count; ++k) {
        const std::size_t slot = (cut.first_id + k) % kCapacity;
        ASSERT_EQ(position[2 * slot], cut.x_mm) << cuts << " cuts, new particle " << cut.first_new + k;
        ASSERT_EQ(position[2 * slot + 1], cut.y_mm) << cuts << " cuts, new particle " << cut.first_new + k;
        ASSERT_EQ(age[slot], 0u);
        ASSERT_EQ(rest[slot], 0u) << "a new particle is awake";
      }
  }
}

// The slot each new particle goes to, found backwards (new_particle_in: what lets the CUDA step emit
// from the thread that owns a slot) is the slot emit_particle writes it to: for bursts that wrap
// round the ring, fill it exactly, or fill a part of it, every slot emit_particle writes names its
// new particle and every other slot names none.
TEST(ParticleEmit, EachSlotKnowsTheNewParticleItReceives) {
  constexpr int kCapacity = 60;  // not a power of two, so that a wrong modulus shows
  std::vector<float> position(2 * kCapacity), velocity(2 * kCapacity), anchor(2 * kCapacity);
  std::vector<std::uint32_t> age(kCapacity), rest(kCapacity);
  ParticleArgs a{};
  a.model = pair_model();
  a.arrays.capacity = kCapacity;
  a.arrays.position = position.data();
  a.arrays.velocity = velocity.data();
  a.arrays.age = age.data();
  a.arrays.rest = rest.data();
  a.arrays.anchor = anchor.data();
  for (const std::uint64_t first_id : {0ull, 50ull, 59ull, 60ull, 1000003ull})
    for (const std::uint32_t cuts : {0u, 1u, 3u, 15u}) {
      std::vector<Emitter> emitters;
      std::uint32_t first_new = 0;
      for (std::uint32_t c = 0; c < cuts; ++c) {  // 4 new particles a cut: 0, 4, 12 or 60 (the ring)
        emitters.push_back({1.0f, 1.0f, first_id + first_new, first_new, 4u});
        first_new += 4;
      }
      a.emitters = emitters.data();
      a.emitter_count = int(cuts);
      a.new_count = int(first_new);
      std::fill(age.begin(), age.end(), kNeverUsed);
      std::vector<int> written(kCapacity, a.new_count);
      for (int e = 0; e < a.new_count; ++e) {
        emit_particle(a, e);
        for (std::size_t slot = 0; slot < kCapacity; ++slot)
          if (age[slot] == 0 && written[slot] == a.new_count) written[slot] = e;
      }
      for (std::size_t slot = 0; slot < kCapacity; ++slot)
        ASSERT_EQ(new_particle_in(a, slot), written[slot]) << "first id " << first_id << ", " << cuts << " cuts, slot " << slot;
    }
}

struct Pull {
  float x = 0.0f, y = 0.0f, company = 0.0f;
};

// The force on a particle at (px, py) moving at (vx, vy) from one at (qx, qy) moving at (wx, wy).
Pull force_on(const ParticleModel& m, float px, float py, float vx, float vy, std::uint32_t slot, float qx, float qy,
              float wx, float wy, std::uint32_t other, std::uint32_t age = 1000000, std::uint32_t other_age = 1000000) {
  PairSums sums;
  add_pair(m, px - qx, py - qy, vx, vy, pair_growth(m, age, other_age), slot, wx, wy, other, &sums);
  return {sums.ax, sums.ay, sums.company};
}

TEST(ParticlePair, ForcesAreEqualAndOppositeToTheBit) {
  const ParticleModel m = pair_model();
  // Overlapping, approaching and sliding; then within cohesion's reach only.
  for (const float gap : {0.13f, 0.19f, 0.21f, 0.25f}) {
    const Pull on_a = force_on(m, 1.00f, 2.00f, 3.0f, -1.0f, 4, 1.00f + gap * 0.8f, 2.00f + gap * 0.6f, -2.0f, 0.5f, 9);
    const Pull on_b = force_on(m, 1.00f + gap * 0.8f, 2.00f + gap * 0.6f, -2.0f, 0.5f, 9, 1.00f, 2.00f, 3.0f, -1.0f, 4);
    EXPECT_GT(std::hypot(on_a.x, on_a.y), 0.0f) << gap;
    EXPECT_EQ(on_a.x, -on_b.x) << gap;
    EXPECT_EQ(on_a.y, -on_b.y) << gap;
  }
}

TEST(ParticlePair, SpringAndDashpotPushCohesionPullsAndNothingBeyondTheRange) {
  const ParticleModel m = pair_model();
  // Overlap 0.2 − 0.15 = 0.05 mm along +x, approaching at 5 mm/s: k·0.05 + c·5 pushes a towards −x,
  // and cohesion (full, in contact) pulls it back towards +x.
  const Pull head_on = force_on(m, 1.0f, 1.0f, 5.0f, 0.0f, 0, 1.15f, 1.0f, 0.0f, 0.0f, 1);
  const double expected = -(double(m.stiffness) * 0.05 + double(m.damping) * 5.0 - double(m.cohesion));
  EXPECT_NEAR(head_on.x, expected, 1e-5 * std::abs(expected));
  EXPECT_EQ(head_on.y, 0.0f);
  // Touching lightly while separating fast: the dashpot would pull; it may not. Only cohesion pulls.
  const Pull parting = force_on(m, 1.0f, 1.0f, -50.0f, 0.0f, 0, 1.1999f, 1.0f, 0.0f, 0.0f, 1);
  EXPECT_FLOAT_EQ(parting.x, m.cohesion);
  // Halfway between contact and the range, cohesion is a quarter of its full pull.
  const float halfway = (m.diameter_mm + m.range_mm) / 2;
  EXPECT_NEAR(force_on(m, 1.0f, 1.0f, 0.0f, 0.0f, 0, 1.0f + halfway, 1.0f, 0.0f, 0.0f, 1).x, 0.25f * m.cohesion,
              1e-5 * m.cohesion);  // the distance, and so the share, are float32
  // Beyond the range: nothing, and not a neighbour.
  const Pull apart = force_on(m, 1.0f, 1.0f, 0.0f, 0.0f, 0, 1.0f + m.range_mm * 1.0001f, 1.0f, 0.0f, 0.0f, 1);
  EXPECT_EQ(apart.x, 0.0f);
  EXPECT_EQ(apart.company, 0.0f);
}

TEST(ParticlePair, ANewParticlesOverlapsAreShiftedAwayNotPushed) {
  const ParticleModel m = pair_model();
  ASSERT_GT(m.birth_steps, 10.0f);
  // Overlapping by 0.1 mm along x: a full-grown pair pushes; one with a new particle does not, and
  // is shifted apart by half the overlap each instead.
  PairSums grown, newborn;
  add_pair(m, 1.0f - 1.1f, 0.0f, 0.0f, 0.0f, pair_growth(m, 1000000, 1000000), 0, 0.0f, 0.0f, 1, &grown);
  add_pair(m, 1.0f - 1.1f, 0.0f, 0.0f, 0.0f, pair_growth(m, 3, 1000000), 0, 0.0f, 0.0f, 1, &newborn);
  EXPECT_LT(grown.ax, 0.0f);
  EXPECT_EQ(grown.hx, 0.0f);
  EXPECT_EQ(newborn.ax, 0.0f);
  EXPECT_NEAR(newborn.hx, -0.05f, 1e-6f);
  EXPECT_EQ(newborn.company, grown.company);  // a neighbour all the same
  // In the second half of its birth, the force grows from nothing to whole.
  const std::uint32_t three_quarters = std::uint32_t(0.75f * m.birth_steps);
  PairSums growing;
  add_pair(m, 1.0f - 1.1f, 0.0f, 0.0f, 0.0f, pair_growth(m, three_quarters, 1000000), 0, 0.0f, 0.0f, 1, &growing);
  EXPECT_EQ(growing.hx, 0.0f);
  EXPECT_NEAR(growing.ax, grown.ax * (float(three_quarters) - 0.5f * m.birth_steps) / (0.5f * m.birth_steps),
              1e-5f * std::abs(grown.ax));
}

TEST(ParticlePair, CoincidentParticlesArePushedApartOppositely) {
  const ParticleModel m = pair_model();
  for (std::uint32_t other = 1; other < 50; ++other) {
    const Pull on_a = force_on(m, 3.0f, 3.0f, 0.0f, 0.0f, 0, 3.0f, 3.0f, 0.0f, 0.0f, other);
    const Pull on_b = force_on(m, 3.0f, 3.0f, 0.0f, 0.0f, other, 3.0f, 3.0f, 0.0f, 0.0f, 0);
    EXPECT_NEAR(std::hypot(on_a.x, on_a.y), m.stiffness * m.diameter_mm - m.cohesion, 1e-5 * m.stiffness) << other;
    EXPECT_EQ(on_a.x, -on_b.x) << other;
    EXPECT_EQ(on_a.y, -on_b.y) << other;
  }
}

// A cluster born at one point: each new particle's shift, the sum of half its overlaps along its
// pairs' directions, points away from the others: none is left where the cluster was born. (With
// one hashed direction per pair, a particle's directions could cancel and leave it coincident.)
TEST(ParticlePair, ACoincidentClusterSpreadsOut) {
  const ParticleModel m = pair_model();
  for (const std::uint32_t size : {2u, 3u, 8u, 64u}) {
    for (std::uint32_t i = 0; i < size; ++i) {
      PairSums sums;
      for (std::uint32_t j = 0; j < size; ++j)
        if (j != i) add_pair(m, 0.0f, 0.0f, 0.0f, 0.0f, pair_growth(m, 0, 0), i, 0.0f, 0.0f, j, &sums);
      // Each pair gives d/2 along a unit direction; the pairs do not cancel to less than one
      // pair's worth, so the particle moves at the birth shift's full rate.
      EXPECT_GT(std::hypot(sums.hx, sums.hy), 0.5 * m.diameter_mm) << size << " " << i;
    }
  }
}

// ---- the stability limit -----------------------------------------------------------------------

TEST(ParticleStability, TheLimitSolvesTheFastestModesCondition) {
  // Without damping or drag the hexagonal lattice's fastest mode (ω² = 6k) needs ω·dt < 2.
  EXPECT_NEAR(stable_time_step_s(1.0e6, 0.0, 0.0, 6), 2.0 / std::sqrt(6.0e6), 1e-12);
  // Drag (implicit) widens the limit; the dashpot (explicit) and more contacts narrow it.
  EXPECT_GT(stable_time_step_s(1.0e6, 0.0, 200.0, 6), stable_time_step_s(1.0e6, 0.0, 0.0, 6));
  EXPECT_LT(stable_time_step_s(1.0e6, 200.0, 0.0, 6), stable_time_step_s(1.0e6, 0.0, 0.0, 6));
  EXPECT_LT(stable_time_step_s(1.0e6, 0.0, 0.0, 8), stable_time_step_s(1.0e6, 0.0, 0.0, 6));
  const double k = 4.0e5, c = 100.0, drag = 100.0, dt = stable_time_step_s(k, c, drag, 6);
  EXPECT_NEAR(6 * k * dt * dt + (12 * c - 2 * drag) * dt, 4.0, 1e-9);
  // The defaults' fewest sub-steps are inside the enforced limit, and one fewer is not.
  const Scene scene = test::box_scene(32, 24);
  const ParticleMechanics mech = resolve_particles(scene.effects.get<ParticleParams>(), scene).mechanics;
  EXPECT_NEAR(mech.step_limit_s,
              stable_time_step_s(mech.stiffness_per_s2, mech.damping_per_s,
                                 scene.effects.get<ParticleParams>().drag_per_s, kDesignContacts),
              1e-15);
  EXPECT_LT(mech.dt_s, mech.step_limit_s);
  EXPECT_GE(1.0 / (30.0 * (mech.substeps - 1)), mech.step_limit_s);
}

// A hexagonal pile resting on the floor of a narrow panel (no cohesion, no grip: the bare contact),
// run for `seconds` at `dt_fraction` of the six-contact stability limit. Returns the largest speed
// seen over the last tenth of the run (mm/s), or infinity once anything is not finite.
double largest_late_speed(double dt_fraction, double seconds) {
  ParticleParams p;
  p.cohesion_mm3_s2 = p.pinning_mm3_s2 = p.yield_mm2_s2 = 0.0;
  const int columns = 40, rows = 20;
  Scene scene = test::box_scene(columns * p.diameter_mm, 2.0 * rows * p.diameter_mm, p);
  const ParticleMechanics mech = resolve_particles(p, scene).mechanics;
  scene.effects.get<ParticleParams>().substeps = 1;
  scene.frame_rate_hz = 1.0 / (dt_fraction * stable_time_step_s(mech.stiffness_per_s2, mech.damping_per_s,
                                                                 p.drag_per_s, 6));
  test::ParticleBox box(scene, test::hex_block(scene, columns, rows));
  const long steps = std::lround(seconds / box.dt());
  double late = 0.0;
  for (long s = 0; s < steps; ++s) {
    box.step();
    if (s < steps - steps / 10) continue;
    for (int i = 0; i < box.size(); ++i) {
      if (!std::isfinite(box.speed(i)) || !std::isfinite(box.position(i).x) || !std::isfinite(box.position(i).y))
        return INFINITY;
      late = std::max(late, box.speed(i));
    }
  }
  return late;
}

TEST(ParticleStability, APileSettlesJustInsideTheLimitAndNeverSettlesJustOutside) {
  // Inside: the pile comes to rest (its fastest particle far below the 10 mm/s blood runs at).
  EXPECT_LT(largest_late_speed(0.97, 0.5), 0.01);
  // Outside: roundoff seeds the lattice's fastest mode, which grows every step until contacts open
  // and close with it: the pile boils.
  EXPECT_GT(largest_late_speed(1.03, 0.5), 1.0);
}

}  // namespace
}  // namespace bleedsim