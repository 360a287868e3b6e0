// The film of blood: the splat keeps each particle's volume on any pixel pitch, keeps the shape of
// its footprint where pixels are fine, sums in any order to the same bits, and fades; the
// Beer–Lambert blend's table follows exp(−x) and colours thin films red, pools dark.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/particles/splat_stage.h"
#include "core/physics/splat.h"

namespace bleedsim {
namespace {

constexpr double kUnitRoundoff = 1.0 / 16777216.0;  // float32's: one rounding is within 2⁻²⁴

// A square panel of `size` pixels of `pitch_mm` with the given particles of the default volume, all
// alive (ages given), splatted on the CPU.
struct Film {
  Domain domain;
  std::vector<float> position;
  std::vector<std::uint32_t> age;
  std::vector<std::uint64_t> units;
  std::vector<float> thickness;
  std::vector<std::uint32_t> stamps;
  SplatArgs args{};

  Film(std::vector<float> xy, std::vector<std::uint32_t> ages, float radius_mm, double pitch_mm = 0.01,
       int size = 200)
      : domain{size, size, size * pitch_mm, size * pitch_mm}, position(std::move(xy)), age(std::move(ages)) {
    ParticleParams params;
    params.splat_radius_mm = radius_mm;
    args.lifetime = {1000, 100};
    args.splat = make_splat_model(params, domain);
    args.position = position.data();
    args.age = age.data();
    args.capacity = int(age.size());
    args.grid = domain.grid();
    units.resize(std::size_t(size) * size);
    thickness.resize(units.size());
    args.units = units.data();
    args.thickness_mm = thickness.data();
    stamps.resize(splat_tile_count(args.grid));
    args.tiles = {stamps.data(), splat_tiles_across(args.grid), 1u};
    cpu_twin(args, 2);
    // The twin leaves its sum zero for the next frame: the sum itself, as it added it up.
    for (int slot = 0; slot < args.capacity; ++slot)
      splat_particle(args, slot, [&](std::size_t p, std::uint64_t u) { units[p] += u; }, [](int) {});
  }
  double pixel_mm() const { return domain.width_mm / domain.width_px; }
  double pixel_area_mm2() const { return pixel_mm() * pixel_mm(); }
  std::uint64_t total_units() const { return std::accumulate(units.begin(), units.end(), std::uint64_t(0)); }
  double volume_mm3() const {
    return std::accumulate(thickness.begin(), thickness.end(), 0.0) * pixel_area_mm2();
  }
  // Pixels whose centres lie within r of (x, y): the most that a splat there deposits into.
  int pixels_within(double x, double y, double r) const {
    int n = 0;
    for (int j = 0; j < domain.height_px; ++j)
      for (int i = 0; i < domain.width_px; ++i)
        n += std::hypot((i + 0.5) * pixel_mm() - x, (j + 0.5) * pixel_mm() - y) < r;
    return n;
  }
};

// A lone particle's film holds its blood, V · fade, on pixels from 1/20 of the splat radius to 5×
// it: clear of the edges, exactly between pixel centres (a pixel corner), at the panel's corner
// (a quarter of the footprint on the panel), on an edge. The bound, in two steps:
//  - its blood in film units, T = V · fade / (pixel area · 2⁻²⁴ mm), is computed in float32 (V, the
//    units per mm³ and two products: 4 roundings of 2⁻²⁴) and rounded half up: within
//    ½ + 4 · 2⁻²⁴ · T units;
//  - each of its n deposits is its share T · wₚ / S rounded half up, exactly in integers: the
//    deposits add up to T within n/2 units (n: the pixels whose centres the splat reaches; where
//    it reaches none, all of T goes into one pixel, exactly).
// A share is the integer quotient ⌊(2·blood·weight + total) / (2·total)⌋ (splat.h): its estimate in
// double, corrected, must equal the integer division exactly, over the whole range the splat allows
// (blood < 2³⁰, weight ≤ 2²³, total from a weight up to 2²⁰ of them and beyond) and at the
// quotients where a correction is needed: the estimate of a whole quotient falls just short, or that of
// one just below a whole number reaches it (each removed correction fails this test).
TEST(Splat, AShareIsTheExactIntegerQuotient) {
  const auto exact = [](std::uint64_t blood, std::uint64_t weight, std::uint64_t total) {
    return (2 * blood * weight + total) / (2 * total);
  };
  const std::uint64_t max_blood = std::uint64_t(kMaxDepositUnits) + 1, max_weight = std::uint64_t(kSplatWeightUnits);
  std::vector<std::array<std::uint64_t, 3>> cases = {
      {max_blood, max_weight, max_weight},     {max_blood, max_weight, max_weight + 1}, {max_blood, 1, 1},
      {max_blood, max_weight - 1, max_weight}, {1, 1, 2},                             {3, 1, 2},
      {max_blood, 1, max_weight << 20},        {max_blood, max_weight, 3 * max_weight}, {0, max_weight, 7},
      // Found by search: quotients that are whole, whose estimate falls just below (corrected up) ...
      {531969375, 1978348, 420968219637000},   {747144855, 35334, 3519948840876},       {566537776, 487224, 184020534249216},
      // ... and quotients just below a whole number, whose estimate reaches it (corrected down).
      {987103834, 4220868, 14386925},          {980694921, 7463415, 24309997},          {998224321, 2912337, 5205739}};
  std::uint64_t state = 0x9e3779b97f4a7c15u;  // splitmix64: a fixed stream, so the test is repeatable
  const auto next = [&] {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
  };
  for (int k = 0; k < 1000000; ++k) {
    const std::uint64_t weight = 1 + next() % max_weight;
    const std::uint64_t total = weight + next() % (max_weight << (next() % 21));
    cases.push_back({next() % max_blood, weight, total});
  }
  for (const auto& [blood, weight, total] : cases)
    ASSERT_EQ(share_of(blood, weight, share_divisor(total)), exact(blood, weight, total))
        << "blood " << blood << ", weight " << weight << ", total " << total;
}

TEST(Splat, AParticlesFilmHoldsItsVolumeOnAnyPixelPitch) {
  const float r = 0.2f;
  const double blood_mm3 = ParticleParams{}.particle_volume_mm3;
  for (const double pitch : {0.01, 0.02, 0.05, 0.1, 0.2, 0.4, 1.0}) {
    const int size = std::max(10, int(std::lround(2.0 / pitch)));
    const float side = float(size * pitch), corner = float(std::round(0.37 * size) * pitch);
    const std::vector<std::vector<float>> places = {
        {0.4137f * side, 0.5291f * side}, {corner, corner}, {0.0f, 0.0f}, {0.5f * side + 0.003f, side}};
    for (const std::vector<float>& xy : places) {
      SCOPED_TRACE(testing::Message() << "pitch " << pitch << " mm, particle at (" << xy[0] << ", " << xy[1] << ")");
      const Film film(xy, {0}, r, pitch, size);
      const int n = film.pixels_within(xy[0], xy[1], r);
      const std::uint64_t blood = blood_units(film.args.splat, 1.0f);
      const double exact_units = blood_mm3 / (film.pixel_area_mm2() * kSplatUnitMm);
      EXPECT_LE(std::abs(double(blood) - exact_units), 0.5 + 4.0 * kUnitRoundoff * exact_units);
      EXPECT_LE(std::abs(double(film.total_units()) - double(blood)), 0.5 * n);
      const double held_mm3 = double(film.total_units()) * kSplatUnitMm * film.pixel_area_mm2();
      EXPECT_LE(std::abs(held_mm3 - blood_mm3),
                (0.5 * n + 0.5) * kSplatUnitMm * film.pixel_area_mm2() + 4.0 * kUnitRoundoff * blood_mm3);
    }
  }
}

// A splat that reaches no pixel centre (it lies between them, or is smaller than a pixel) puts all
// of its blood into the pixel holding its centre; one at a pixel corner that reaches the four
// centres around it shares it equally among them. (Half-millimetre pixels: every coordinate here
// is exact in float.)
TEST(Splat, ASplatBetweenPixelCentresKeepsItsBlood) {
  const Film between({1.0f, 0.5f}, {0}, 0.3f, 0.5, 10);  // a pixel corner, 0.354 mm from four centres
  const std::uint64_t blood = blood_units(between.args.splat, 1.0f);
  EXPECT_EQ(between.units[1 * 10 + 2], blood);
  EXPECT_EQ(between.total_units(), blood);

  const Film small({0.3f, 0.2f}, {0}, 0.05f, 0.5, 10);  // R a tenth of a pixel, off its centre
  EXPECT_EQ(small.units[0], blood);
  EXPECT_EQ(small.total_units(), blood);

  const Film shared({1.0f, 0.5f}, {0}, 0.4f, 0.5, 10);  // the same corner, R past the four centres
  const std::uint64_t quarter = shared.units[0 * 10 + 1];
  for (const int p : {0 * 10 + 2, 1 * 10 + 1, 1 * 10 + 2}) EXPECT_EQ(shared.units[p], quarter) << p;
  EXPECT_EQ(shared.total_units(), 4 * quarter);
  EXPECT_LE(std::abs(double(4 * quarter) - double(blood)), 4 * 0.5);
}

// On pixels a twentieth of R the film keeps the footprint's shape: each pixel holds (1 − d²/R²)² of
// the centre's film. Pixels of 1/128 mm and R = 20 of them: distances are exact in float, so the
// bound is the two deposits' rounding (half a unit each, against over 10⁶ units at the centre), the
// two weights' (half of 2⁻²³ each, against the centre's 1) and float32's rounding of d²/R² and of
// the square (2⁻²⁴ of each, twice for d²/R² as the square doubles it).
TEST(Splat, OnFinePixelsTheFilmKeepsTheFootprintsShape) {
  const double pitch = 1.0 / 128.0, r = 20 * pitch;
  const Film film({128.5f / 128.0f, 128.5f / 128.0f}, {0}, float(r), pitch, 256);  // on pixel (128, 128)
  const double centre = double(film.units[128 * 256 + 128]);
  ASSERT_GT(centre, 1.0e6);
  const double allowed = 1.0 / centre + 1.0 / 8388608.0 + 3.0 * kUnitRoundoff;
  for (int j = 100; j <= 156; ++j)
    for (int i = 100; i <= 156; ++i) {
      const double d = std::hypot(i - 128, j - 128) * pitch;
      const double q = std::max(0.0, 1.0 - d * d / (r * r));
      EXPECT_NEAR(double(film.units[j * 256 + i]) / centre, q * q, allowed) << i << ", " << j;
    }
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
  // Half the blood, each within the rounding of its n deposits and of its blood in units.
  const int n = full.pixels_within(1.0, 1.0, 0.2);
  EXPECT_NEAR(fading.volume_mm3(), 0.5 * full.volume_mm3(), (n + 1.0) * kSplatUnitMm * full.pixel_area_mm2());
  EXPECT_EQ(dead.volume_mm3(), 0.0);
}

}  // namespace
}  // namespace bleedsim