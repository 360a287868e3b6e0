// A film with depth's births end by distance (docs/particles.md#births-of-a-film-with-depth): a
// burst of parcels born at one point parts at no more than g/γ, never uphill, and joins the film
// once no other birth is nearer than 0.99 of a diameter. The bounds are issue 36's acceptance bounds
// for such a burst with the model's defaults, not derived here; each note says why the model should
// meet its bound. They are checked at every frame:
//   * no parcel faster than 2·g/γ: a birth moves by its shift, at no more than g/γ, and keeps no
//     velocity of its own beyond the emission's; a parcel that has joined slides at g/γ, and the
//     film the burst leaves, one layer at the births' spacing, may add at most as much again by
//     spreading. (Released at once, the same burst reached the 100 mm/s cap.)
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
#include <string>
#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/io/scenario.h"
#include "core/physics/particles.h"
#include "core/runtime/backend.h"
#include "core/simulation/simulation.h"
#include "tests/effects/hard_case_check.h"
#include "tests/runtime/field_values.h"

namespace bleedsim {
namespace {

using test::field_values;

constexpr double kAboveTheWoundMm = 1.0;
constexpr double kRestSpeed = 0.1;  // mm/s

struct BurstSummary {
  double fastest = 0.0;       // mm/s, any frame
  double highest_mm = 0.0;    // the farthest any parcel was above the wound, mm
  double last_birth_s = 0.0;  // the last frame with a parcel being born
};

enum class AtTheEnd { at_rest, may_move };

void check_burst(const std::string& name, BackendChoice::Want backend, std::uint64_t births, AtTheEnd end) {
  Scene scene = test::load_hard(name);
  ASSERT_EQ(scene.cuts.size(), 1u);
  const ParticleParams& params = scene.effects.get<ParticleParams>();
  ASSERT_TRUE(params.film_depth);
  const ParticleModel m = resolve_particles(scene).model;
  const double wound_y = scene.cuts[0].y_mm;
  const double bound = 2.0 * std::hypot(params.gravity_x_mm_s2, params.gravity_y_mm_s2) / params.drag_per_s;
  const std::int64_t frames = scene.frame_count();
  Simulation sim(std::move(scene), BackendChoice{backend, 2});
  BurstSummary s;
  std::vector<float> velocity;
  std::vector<std::uint32_t> age, rest;
  for (std::int64_t k = 0; k < frames; ++k) {
    sim.step();
    const std::vector<float> position = field_values<float>(sim, "particles/position");
    velocity = field_values<float>(sim, "particles/velocity");
    age = field_values<std::uint32_t>(sim, "particles/age");
    rest = field_values<std::uint32_t>(sim, "particles/rest");
    for (std::size_t i = 0; i < age.size(); ++i) {
      if (!is_alive(m, age[i])) continue;
      const double speed = std::hypot(double(velocity[2 * i]), double(velocity[2 * i + 1]));
      const double above = wound_y - double(position[2 * i + 1]);
      ASSERT_TRUE(std::isfinite(speed) && std::isfinite(above)) << name << ", frame " << k << ", slot " << i;
      s.fastest = std::max(s.fastest, speed);
      s.highest_mm = std::max(s.highest_mm, above);
      if (rest[i] == kBeingBorn) s.last_birth_s = sim.time_s();
    }
    ASSERT_LE(s.fastest, bound) << name << ", frame " << k << " (t = " << sim.time_s() << " s)";
    ASSERT_LE(s.highest_mm, kAboveTheWoundMm) << name << ", frame " << k << " (t = " << sim.time_s() << " s)";
  }
  std::cout << name << ": fastest " << s.fastest << " mm/s (bound " << bound << "), highest " << s.highest_mm
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

// Minutes on two CPU cores: the GPU machine runs it (scripts/gpu-check's device tests).
TEST(FilmBirths, ABurstOf12000AtOnePointPartsWithoutABlastOnCuda) {
  std::string why;
  if (!cuda_device_available(&why)) GTEST_SKIP() << "no CUDA device: " << why;
  check_burst("film-burst-12k", BackendChoice::Want::cuda, 12000u, AtTheEnd::may_move);
}

}  // namespace
}  // namespace bleedsim
