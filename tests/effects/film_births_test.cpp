// A film with depth's births end by distance (docs/particles.md#births-of-a-film-with-depth): a
// burst of parcels born at one point parts at no more than g/γ, never uphill, and joins the film
// once no other birth is nearer than 0.99 of a diameter. The bounds are issue 36's acceptance bounds
// for such a burst with the model's defaults, not derived here; each note says why the model should
// meet its bound. They are checked at every frame:
//   * no parcel faster than 2·g/γ: a birth moves by its shift, at no more than g/γ, and keeps no
//     velocity of its own beyond the emission's; a parcel that has joined slides at g/γ, and the
//     film the burst leaves, one layer at the births' spacing, may add at most as much again by
//     spreading; births still crowded when birth_s runs out join over kFilmJoinS, not at once.
//     (Released at once, the same burst reached the 100 mm/s cap.) A frame's end shows one
//     sub-step's velocity, so the distance each parcel moved over the frame is held to the bound
//     too: a mean over the frame's sub-steps, it is no more than the fastest of them.
//   * no parcel more than 1 mm above (uphill of) the wound: births are never shifted uphill, so only
//     the film's own spreading, against gravity and the mucosa's grip, carries blood above the
//     wound. (Released at once: 1.9 mm.)
// and at the end, that every birth has ended and the accounting is exact; and for the burst of
// 1,200, that the blood has stopped (the rest speed, 0.1 mm/s). The 12,000 are 48 mm³, far
// more than a drop the mucosa holds: they run down to the floor and still slump there at 8 s
// (2.2 mm/s on the H100), which is not what the case is about.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/io/scenario.h"
#include "core/physics/particles.h"
#include "core/runtime/backend.h"
#include "core/simulation/simulation.h"
#include "tests/effects/hard_case_check.h"
#include "tests/test_paths.h"
#include "tests/runtime/field_values.h"

namespace bleedsim {
namespace {

using test::field_values;

constexpr double kAboveTheWoundMm = 1.0;
constexpr double kRestSpeed = 0.1;  // mm/s

struct BurstSummary {
  double fastest = 0.0;       // mm/s, any frame
  double fastest_mean = 0.0;  // mm/s: the farthest a parcel moved in a frame, over the frame's period
  double highest_mm = 0.0;    // the farthest any parcel was above the wound, mm
  double last_birth_s = 0.0;  // the last frame with a parcel being born
};

enum class AtTheEnd { at_rest, may_move };

void check_burst(const std::string& name, BackendChoice::Want backend, std::uint64_t births, AtTheEnd end,
                 std::optional<double> birth_s = std::nullopt) {
  Scene scene = test::load_hard(name);
  if (birth_s) scene.effects.get<ParticleParams>().birth_s = *birth_s;
  ASSERT_EQ(scene.cuts.size(), 1u);
  const ParticleParams& params = scene.effects.get<ParticleParams>();
  ASSERT_TRUE(params.film_depth);
  const ParticleModel m = resolve_particles(scene).model;
  const double wound_y = scene.cuts[0].y_mm;
  const double bound = 2.0 * std::hypot(params.gravity_x_mm_s2, params.gravity_y_mm_s2) / params.drag_per_s;
  const std::int64_t frames = scene.frame_count();
  const double frame_rate_hz = scene.frame_rate_hz;
  Simulation sim(std::move(scene), BackendChoice{backend, 2});
  BurstSummary s;
  std::vector<float> velocity, position;
  std::vector<std::uint32_t> age, rest;
  for (std::int64_t k = 0; k < frames; ++k) {
    sim.step();
    const std::vector<float> before = position;
    const std::vector<std::uint32_t> age_before = age;
    position = field_values<float>(sim, "particles/position");
    velocity = field_values<float>(sim, "particles/velocity");
    age = field_values<std::uint32_t>(sim, "particles/age");
    rest = field_values<std::uint32_t>(sim, "particles/rest");
    for (std::size_t i = 0; i < age.size(); ++i) {
      if (!is_alive(m, age[i])) continue;
      const double speed = std::hypot(double(velocity[2 * i]), double(velocity[2 * i + 1]));
      const double above = wound_y - double(position[2 * i + 1]);
      ASSERT_TRUE(std::isfinite(speed) && std::isfinite(above)) << name << ", frame " << k << ", slot " << i;
      s.fastest = std::max(s.fastest, speed);
      // No slot is reused (the capacity exceeds the births): a slot alive a frame ago holds the same
      // parcel, and the speed it kept up over the frame is one its sub-steps reached.
      if (!age_before.empty() && is_alive(m, age_before[i]))
        s.fastest_mean = std::max(s.fastest_mean, std::hypot(double(position[2 * i]) - before[2 * i],
                                                             double(position[2 * i + 1]) - before[2 * i + 1]) *
                                                      frame_rate_hz);
      s.highest_mm = std::max(s.highest_mm, above);
      if (rest[i] == kBeingBorn) s.last_birth_s = sim.time_s();
    }
    ASSERT_LE(s.fastest, bound) << name << ", frame " << k << " (t = " << sim.time_s() << " s)";
    ASSERT_LE(s.fastest_mean, bound) << name << ", frame " << k << " (t = " << sim.time_s() << " s): moved over it";
    ASSERT_LE(s.highest_mm, kAboveTheWoundMm) << name << ", frame " << k << " (t = " << sim.time_s() << " s)";
  }
  std::cout << name << ": fastest " << s.fastest << " mm/s, over a frame " << s.fastest_mean << " mm/s (bound "
            << bound << "), highest " << s.highest_mm
            << " mm above the wound (bound " << kAboveTheWoundMm << "), the last birth ended by " << s.last_birth_s
            << " s" << std::endl;
  const std::vector<std::uint64_t> counts = field_values<std::uint64_t>(sim, "particles/accounting");
  EXPECT_EQ(counts.at(0), births);  // emitted: the flow over 1 ms in parcels of 0.004 mm³
  EXPECT_EQ(counts.at(1), births);  // alive: nothing expired or overwritten
  double fastest_at_end = 0.0;
  for (std::size_t i = 0; i < age.size(); ++i) {
    if (!is_alive(m, age[i])) continue;
    EXPECT_NE(rest[i], kBeingBorn) << name << ": slot " << i << " is still being born at the end";
    fastest_at_end = std::max(fastest_at_end, std::hypot(double(velocity[2 * i]), double(velocity[2 * i + 1])));
  }
  if (end == AtTheEnd::at_rest) {
    EXPECT_LE(fastest_at_end, kRestSpeed) << name;
  }
}

TEST(FilmBirths, ABurstOf1200AtOnePointPartsWithoutABlast) {
  check_burst("film-burst", BackendChoice::Want::cpu, 1200u, AtTheEnd::at_rest);
}

// The same burst with births cut short at 0.3 s, a quarter of the time they take to part: most run
// out crowded, as the 12,000's do at 3 s, and join over kFilmJoinS within the same bounds.
TEST(FilmBirths, ABurstWhoseBirthsRunOutCrowdedJoinsWithoutABlast) {
  check_burst("film-burst", BackendChoice::Want::cpu, 1200u, AtTheEnd::at_rest, 0.3);
}

// Minutes on two CPU cores: the GPU machine runs it (scripts/gpu-check's device tests).
TEST(FilmBirths, ABurstOf12000AtOnePointPartsWithoutABlastOnCuda) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "no CUDA device: " << why;
  check_burst("film-burst-12k", BackendChoice::Want::cuda, 12000u, AtTheEnd::may_move);
}

// The R2 sequence's points k ids apart are ‖k·α‖ apart on the unit torus wherever the run starts
// (α = (1/φ₂, 1/φ₂²), φ₂ the real root of x³ = x + 1), and the plane distance is never less: the
// closest two of `n` consecutive births at one cut, in units of the jitter's square.
double closest_of_consecutive(int n) {
  double phi = 1.3;
  for (int i = 0; i < 50; ++i) phi -= (phi * phi * phi - phi - 1.0) / (3.0 * phi * phi - 1.0);  // Newton
  const double alpha[2] = {1.0 / phi, 1.0 / (phi * phi)};
  double closest = 1.0;
  for (int k = 1; k < n; ++k) {
    double sq = 0.0;
    for (const double a : alpha) {
      const double f = k * a - std::floor(k * a);
      sq += std::min(f, 1.0 - f) * std::min(f, 1.0 - f);
    }
    closest = std::min(closest, std::sqrt(sq));
  }
  return closest;
}

// A steady wound's births each join the film in the step they are born, at every size of issue
// 36's ladder below the shipped one (scenarios/studies/film-ladder.toml at d/4 … d/16, its volume
// scaled by f² as the study scales it). A step's births at the cut are consecutive ids, whose R2
// points keep closest_of_consecutive() of the jitter's square apart: the test first asserts that
// this is at least kBirthsApart·d at each size, for the most births a step brings, so that no birth
// is crowded by another; none can then be found still being born at the end of a frame. With
// independent draws for the jitter (the contact's births), the finest size's 2.4 births a step in
// 8 × 8 diameters land within a diameter of each other in about one step in seven, crowd, and part
// over tens of steps: some frame ends find them being born.
TEST(FilmBirths, ASteadyWoundsBirthsJoinInTheStepTheyAreBornAtEverySize) {
  for (const double f : {0.25, 0.125, 0.0625}) {
    Scene scene = load_scenario(test::source_dir() + "/scenarios/studies/film-ladder.toml").scene;
    scene.duration_s = 0.2;
    ParticleParams& params = scene.effects.get<ParticleParams>();
    params.diameter_mm *= f;
    params.particle_volume_mm3 *= f * f;
    params.capacity = 1 << 16;
    ASSERT_EQ(scene.cuts.size(), 1u);
    const double dt = 1.0 / (scene.frame_rate_hz * params.substeps);
    const double births_per_step = scene.cuts[0].flow_mm3_per_s_per_mm * scene.cuts[0].wound_mm * dt /
                                   params.particle_volume_mm3;
    const int most = int(std::ceil(births_per_step));
    const double apart = 2.0 * params.jitter_mm * closest_of_consecutive(most);
    ASSERT_GE(apart, double(kBirthsApart) * params.diameter_mm) << "d = " << params.diameter_mm << " mm";
    std::cout << "d = " << params.diameter_mm << " mm: " << births_per_step << " births a step"
              << (most > 1 ? ", at least " + std::to_string(apart) + " mm apart" : "") << std::endl;
    const ParticleModel m = resolve_particles(scene).model;
    const std::int64_t frames = scene.frame_count();
    Simulation sim(std::move(scene), BackendChoice{BackendChoice::Want::cpu, 2});
    for (std::int64_t k = 0; k < frames; ++k) {
      sim.step();
      const std::vector<std::uint32_t> age = field_values<std::uint32_t>(sim, "particles/age");
      const std::vector<std::uint32_t> rest = field_values<std::uint32_t>(sim, "particles/rest");
      for (std::size_t i = 0; i < age.size(); ++i)
        ASSERT_FALSE(is_alive(m, age[i]) && rest[i] == kBeingBorn)
            << "d = " << m.diameter_mm << " mm, frame " << k << ": slot " << i << " is still being born";
    }
    EXPECT_GT(field_values<std::uint64_t>(sim, "particles/accounting").at(0), 0u);
  }
}

}  // namespace
}  // namespace bleedsim
