// The film of blood: the splat keeps the blood's volume, sums in any order to the same bits, and
// fades; the Beer–Lambert blend's table follows exp(−x) and colours thin films red, pools dark.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/physics/blend.h"
#include "core/physics/splat.h"
#include "core/effects/splat_stage.h"

namespace bleedsim {
namespace {

// A 0.01 mm/px panel with the given particles, all alive (ages given), splatted on the CPU.
struct Film {
  std::vector<float> position;
  std::vector<std::uint32_t> age;
  std::vector<std::uint64_t> units;
  std::vector<float> thickness;
  SplatArgs args{};

  Film(std::vector<float> xy, std::vector<std::uint32_t> ages, float radius_mm, int size = 200)
      : position(std::move(xy)), age(std::move(ages)) {
    ParticleParams params;
    params.splat_radius_mm = radius_mm;
    args.lifetime = {1000, 100};
    args.splat = make_splat_model(params);
    args.position = position.data();
    args.age = age.data();
    args.capacity = int(age.size());
    args.grid = PixelGrid{size, size, 0.01f, 0.01f};
    units.resize(std::size_t(size) * size);
    thickness.resize(units.size());
    args.units = units.data();
    args.thickness_mm = thickness.data();
    cpu_twin(args, 2);
  }
  double volume_mm3() const {
    const double pixel_area = 0.01 * 0.01;
    return std::accumulate(thickness.begin(), thickness.end(), 0.0) * pixel_area;
  }
};

TEST(Splat, AParticlesFilmHoldsItsVolume) {
  const Film film({1.0f, 1.0f}, {0}, 0.2f);  // R = 20 px, well inside the 2 mm panel
  EXPECT_NEAR(film.volume_mm3(), ParticleParams{}.particle_volume_mm3, 0.004 * 0.005);
  // Thickest at the centre, (1 − d²/R²)² of it halfway out, nothing beyond R.
  const float centre = film.thickness[100 * 200 + 100];
  EXPECT_GT(centre, 0.0f);
  EXPECT_EQ(film.thickness[100 * 200 + 100 + 25], 0.0f);
}

TEST(Splat, TheSumDoesNotDependOnTheParticlesOrder) {
  std::vector<float> xy;
  std::vector<std::uint32_t> ages;
  for (int k = 0; k < 300; ++k) {
    xy.push_back(0.5f + 0.0031f * float((k * 37) % 300));
    xy.push_back(0.5f + 0.0029f * float((k * 91) % 300));
    ages.push_back(std::uint32_t((k * 13) % 1000));
  }
  const Film forward(xy, ages, 0.1f);
  std::vector<float> xy_reversed;
  std::vector<std::uint32_t> ages_reversed(ages.rbegin(), ages.rend());
  for (int k = 299; k >= 0; --k) xy_reversed.insert(xy_reversed.end(), {xy[2 * k], xy[2 * k + 1]});
  const Film backward(xy_reversed, ages_reversed, 0.1f);
  EXPECT_EQ(forward.units, backward.units);
  EXPECT_EQ(forward.thickness, backward.thickness);
}

TEST(Splat, AFadingParticleLeavesLessAndADeadOneNothing) {
  const Film full({1.0f, 1.0f}, {0}, 0.2f);
  const Film fading({1.0f, 1.0f}, {950}, 0.2f);  // 50 of its 100 fade steps left: half
  const Film dead({1.0f, 1.0f}, {1000}, 0.2f);
  EXPECT_NEAR(fading.volume_mm3(), 0.5 * full.volume_mm3(), 1e-7);
  EXPECT_EQ(dead.volume_mm3(), 0.0);
}

TEST(BeerLambert, TheTableFollowsTheExponential) {
  std::vector<float> table(kTransmissionEntries);
  fill_transmission_table(table.data());
  EXPECT_EQ(transmitted(table.data(), 0.0f), 1.0f);
  for (double x = 0.0; x < 40.0; x += 0.0137) {
    const double exact = x < 32.0 ? std::exp(-x) : std::exp(-32.0);
    // Linear interpolation at steps of 1/64 errs by at most (1/64)²/8 of the value.
    EXPECT_NEAR(transmitted(table.data(), float(x)), exact, 3.1e-5 * exact + 1e-7) << x;
  }
}

TEST(BeerLambert, AThinFilmReadsRedAndAPoolDark) {
  std::vector<float> table(kTransmissionEntries);
  fill_transmission_table(table.data());
  const std::uint8_t tissue[4] = {200, 150, 140, 255};
  std::uint8_t bare[4], thin[4], pool[4];
  blend_pixel(tissue, 0.0f, 0.0f, table.data(), bare);
  blend_pixel(tissue, 0.0f, 0.02f, table.data(), thin);
  blend_pixel(tissue, 0.0f, 1.0f, table.data(), pool);
  EXPECT_EQ(std::vector<int>(bare, bare + 4), (std::vector<int>{200, 150, 140, 255}));
  // 0.02 mm keeps e^−0.08 of the red (185) and e^−0.8, e^−0.9 of green and blue (67, 57).
  EXPECT_EQ(std::vector<int>(thin, thin + 4), (std::vector<int>{185, 67, 57, 255}));
  // 1 mm: e^−4 of the red, nothing visible of green and blue.
  EXPECT_EQ(std::vector<int>(pool, pool + 4), (std::vector<int>{4, 0, 0, 255}));
}

}  // namespace
}  // namespace bleedsim
