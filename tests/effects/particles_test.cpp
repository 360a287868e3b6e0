// The particle model's parts, each against something that does not share its code: the accounting
// against a slot-by-slot replay of the ring buffer, contacts against Newton's third law, the
// stability limit against a pile run just inside and just outside it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "core/runtime/backend.h"
#include "core/effects/particle_accounting.h"
#include "core/effects/particle_buffers.h"
#include "core/effects/particle_model.h"
#include "core/physics/particles.h"

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
  scene.particles = ParticleParams{};
  scene.particles->cell_mm = 0.45;
  scene.particles->lifetime_s = 2.0;
  scene.particles->fade_s = 0.3;
  const ParticleModel m = make_particle_model(scene);
  EXPECT_EQ(particle_lifetime(scene).steps, m.lifetime.steps);
  EXPECT_EQ(particle_lifetime(scene).fade_steps, m.lifetime.fade_steps);
  EXPECT_EQ(m.lifetime.steps, 2400u);  // 2 s at 30 Hz × 40 sub-steps
  EXPECT_EQ(particle_cell_count(scene), std::size_t(cell_count(m)));
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

// ---- contacts ----------------------------------------------------------------------------------

ParticleModel contact_model() {
  ParticleModel m{};
  m.diameter_mm = 0.2f;
  m.radius_mm = 0.1f;
  m.diameter_sq = 0.04f;
  m.stiffness = 4.0e5f;
  m.damping = 100.0f;
  return m;
}

struct Push {
  float x = 0.0f, y = 0.0f;
};

Push push_on(const ParticleModel& m, float px, float py, float vx, float vy, std::uint32_t slot, float qx, float qy,
             float wx, float wy, std::uint32_t other) {
  Push a;
  add_contact(m, px, py, vx, vy, slot, qx, qy, wx, wy, other, &a.x, &a.y);
  return a;
}

TEST(ParticleContact, PushesAreEqualAndOppositeAndZeroOutOfReach) {
  const ParticleModel m = contact_model();
  const Push on_a = push_on(m, 1.00f, 2.00f, 3.0f, -1.0f, 4, 1.12f, 2.09f, -2.0f, 0.5f, 9);
  const Push on_b = push_on(m, 1.12f, 2.09f, -2.0f, 0.5f, 9, 1.00f, 2.00f, 3.0f, -1.0f, 4);
  EXPECT_GT(std::hypot(on_a.x, on_a.y), 0.0f);
  EXPECT_FLOAT_EQ(on_a.x, -on_b.x);
  EXPECT_FLOAT_EQ(on_a.y, -on_b.y);
  // Overlap 0.2 − 0.15 = 0.05 mm along +x, approaching at 5 mm/s: k·0.05 + c·5 pushes a to −x.
  const Push head_on = push_on(m, 1.0f, 1.0f, 5.0f, 0.0f, 0, 1.15f, 1.0f, 0.0f, 0.0f, 1);
  EXPECT_NEAR(head_on.x, -(4.0e5 * 0.05 + 100.0 * 5.0), 0.5);
  EXPECT_FLOAT_EQ(head_on.y, 0.0f);
  const Push apart = push_on(m, 1.0f, 1.0f, 0.0f, 0.0f, 0, 1.2001f, 1.0f, 0.0f, 0.0f, 1);
  EXPECT_EQ(apart.x, 0.0f);
  EXPECT_EQ(apart.y, 0.0f);
}

TEST(ParticleContact, CoincidentParticlesArePushedApartOppositely) {
  const ParticleModel m = contact_model();
  for (std::uint32_t other = 1; other < 50; ++other) {
    const Push on_a = push_on(m, 3.0f, 3.0f, 0.0f, 0.0f, 0, 3.0f, 3.0f, 0.0f, 0.0f, other);
    const Push on_b = push_on(m, 3.0f, 3.0f, 0.0f, 0.0f, other, 3.0f, 3.0f, 0.0f, 0.0f, 0);
    EXPECT_NEAR(std::hypot(on_a.x, on_a.y), 4.0e5 * 0.2, 1.0) << other;  // full overlap, unit direction
    EXPECT_EQ(on_a.x, -on_b.x) << other;
    EXPECT_EQ(on_a.y, -on_b.y) << other;
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
  // The enforced limit keeps a margin for eight contacts: the defaults' 40 sub-steps at 30 Hz fit.
  const ParticleParams defaults;
  EXPECT_NEAR(particle_step_limit_s(defaults), stable_time_step_s(k, c, drag, kDesignContacts), 1e-15);
  EXPECT_LT(1.0 / (30.0 * defaults.substeps), particle_step_limit_s(defaults));
}

// A hexagonal pile resting on the floor of a narrow panel, run for `steps` at `dt_fraction` of the
// six-contact stability limit with the default contact and gravity, on the CPU reference. Returns the largest speed seen
// over the last tenth of the run (mm/s), or infinity once anything is not finite.
double largest_late_speed(double dt_fraction, int steps) {
  Scene scene;
  scene.frame_rate_hz = 30.0;
  scene.particles = ParticleParams{};
  ParticleParams& p = *scene.particles;
  const double dt = dt_fraction * stable_time_step_s(p.stiffness_per_s2, p.damping_per_s, p.drag_per_s, 6);
  p.substeps = 1;
  scene.frame_rate_hz = 1.0 / dt;
  const int columns = 40, rows = 20;
  const double d = p.diameter_mm, row_height = d * std::sqrt(3.0) / 2.0;
  scene.domain = Domain{400, 400, columns * d, 2.0 * rows * row_height + d};
  const ParticleModel m = make_particle_model(scene);

  std::unique_ptr<Backend> cpu = make_cpu_backend(1);
  const int n = columns * rows - rows / 2;  // odd rows, shifted half a particle, hold one fewer
  ParticleArrays a{};
  a.capacity = n;
  Buffer position = cpu->allocate(2 * n * sizeof(float)), velocity = cpu->allocate(2 * n * sizeof(float)),
         age = cpu->allocate(n * sizeof(std::uint32_t));
  a.position = position.as<float>();
  a.velocity = velocity.as<float>();
  a.age = age.as<std::uint32_t>();
  Buffer scratch = cpu->allocate(particle_scratch_bytes(cell_count(m), n, 0));
  point_particle_scratch(a, cell_count(m), scratch.data(), 0);
  clear_particles(*cpu, a);
  int slot = 0;
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < columns - row % 2; ++col, ++slot) {
      a.position[2 * slot] = float((col + 0.5 + 0.5 * (row % 2)) * d);
      a.position[2 * slot + 1] = float(scene.domain.height_mm - d / 2 - row * row_height);
      a.age[slot] = 0;
    }
  ParticleArgs args{};
  args.model = m;
  args.arrays = a;
  args.live_count = n;  // every slot holds a particle
  args.first_live_slot = 0;
  double late = 0.0;
  for (int s = 0; s < steps; ++s) {
    for (ParticlePhase phase : {ParticlePhase::bin, ParticlePhase::collide, ParticlePhase::integrate})
      cpu_twin(phase, args, 1);
    if (s < steps - steps / 10) continue;
    for (int i = 0; i < n; ++i) {
      const double speed = std::hypot(a.velocity[2 * i], a.velocity[2 * i + 1]);
      if (!std::isfinite(speed) || !std::isfinite(a.position[2 * i]) || !std::isfinite(a.position[2 * i + 1]))
        return INFINITY;
      late = std::max(late, speed);
    }
  }
  return late;
}

TEST(ParticleStability, APileSettlesJustInsideTheLimitAndNeverSettlesJustOutside) {
  // Inside: the pile comes to rest (last speeds of ~0.001 mm/s, against the ~20 mm/s blood runs at).
  EXPECT_LT(largest_late_speed(0.97, 3000), 0.01);
  // Outside: roundoff seeds the lattice's fastest mode, which grows every step until contacts open
  // and close with it: the pile boils (~16 mm/s at 3% past the limit, ~80 mm/s at 30%).
  EXPECT_GT(largest_late_speed(1.03, 3000), 10.0);
}

}  // namespace
}  // namespace bleedsim
