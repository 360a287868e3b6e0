// The splat reads back only the tiles its deposits reach, and leaves their sums zero (core/physics/
// splat.h): frame after frame, while the blood moves from tile to tile, the film must be that of the
// same particles summed afresh into a zeroed panel, on both backends, byte for byte, the sum zero
// again after each frame; and the film the splat downsamples in its own pass, the blur's
// downsample of that film.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/particles/splat_stage.h"
#include "core/physics/splat.h"
#include "core/runtime/backend.h"

namespace bleedsim {
namespace {

struct Case {
  BackendChoice::Want backend;
  float radius_mm;      // 0.2: footprints of some 8 × 10 pixels; 0.01: none reaches a pixel centre
  std::uint32_t first;  // the stamp every tile has before the first frame, and the frame before's
  int factor;           // the blur's downsample, done in the splat's pass (0: none)
};

class SplatTiles : public testing::TestWithParam<Case> {};

constexpr int kParticles = 240;
constexpr int kFrames = 7;
constexpr std::uint32_t kLifetimeSteps = 1000;

// Frame f's particles: a cluster that crosses the panel from its top-left corner to past its
// bottom-right one, so each frame reaches tiles the last did not and leaves some the last reached;
// a few on and beyond the edges, every seventh dead, and in frame 3 every one dead.
void particles_of_frame(int f, const Domain& d, std::vector<float>* xy, std::vector<std::uint32_t>* ages) {
  xy->clear();
  ages->clear();
  std::uint32_t state = 2463534242u + 977u * std::uint32_t(f);  // xorshift32: a fixed stream
  const auto unit = [&] {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return float(state % 10007u) / 10006.0f;
  };
  const float cx = float(d.width_mm) * (-0.1f + 0.2f * float(f)), cy = float(d.height_mm) * (0.05f + 0.16f * float(f));
  for (int k = 0; k < kParticles; ++k) {
    float x = cx + (unit() - 0.5f) * 0.4f * float(d.width_mm), y = cy + (unit() - 0.5f) * 0.4f * float(d.height_mm);
    if (k % 23 == 0) x = k % 2 ? -0.3f : float(d.width_mm) + 0.05f * float(k % 5);  // off the panel's sides
    if (k % 29 == 0) y = k % 2 ? 0.0f : float(d.height_mm);                          // on its top and bottom edges
    xy->insert(xy->end(), {x, y});
    ages->push_back(f == 3 || k % 7 == 0 ? kLifetimeSteps : std::uint32_t(k % 400));
  }
}

TEST_P(SplatTiles, FrameAfterFrameTheFilmIsThatOfAFreshSum) {
  const Case c = GetParam();
  std::string why;
  if (c.backend == BackendChoice::Want::cuda && !cuda_device_available(&why)) GTEST_SKIP() << "no CUDA device: " << why;
  const std::unique_ptr<Backend> backend = select_backend(BackendChoice{c.backend, 2}).backend;

  // 150 × 97 pixels of 0.05 × 0.04 mm: tiles cut short at the right and the bottom.
  const Domain domain{150, 97, 7.5, 3.88};
  ParticleParams params;
  params.splat_radius_mm = c.radius_mm;
  SplatArgs a{};
  a.lifetime = {kLifetimeSteps, 100};
  a.splat = make_splat_model(params, domain);
  a.capacity = kParticles;
  a.grid = domain.grid();
  const std::size_t pixels = std::size_t(domain.width_px) * domain.height_px;
  const Buffer position = backend->allocate(2 * kParticles * sizeof(float)),
               age = backend->allocate(kParticles * sizeof(std::uint32_t)),
               units = backend->allocate(pixels * sizeof(std::uint64_t)), film = backend->allocate(pixels * sizeof(float)),
               stamps = backend->allocate(splat_tile_count(a.grid) * sizeof(std::uint32_t));
  backend->upload(units.data(), std::vector<std::uint64_t>(pixels, 0u).data(), units.bytes());
  const std::vector<std::uint32_t> unstamped(splat_tile_count(a.grid), c.first);
  backend->upload(stamps.data(), unstamped.data(), stamps.bytes());
  a.position = position.as<const float>();
  a.age = age.as<const std::uint32_t>();
  a.units = units.as<std::uint64_t>();
  a.thickness_mm = film.as<float>();
  a.tiles = {stamps.as<std::uint32_t>(), splat_tiles_across(a.grid), c.first};
  Buffer low;
  if (c.factor > 0) {
    BlurArgs& b = a.downsample;
    b.width = domain.width_px;
    b.height = domain.height_px;
    b.factor = c.factor;
    b.low_width = (b.width + c.factor - 1) / c.factor;
    b.low_height = (b.height + c.factor - 1) / c.factor;
    low = backend->allocate(std::size_t(b.low_width) * b.low_height * sizeof(float));
    b.film = a.thickness_mm;
    b.low = low.as<float>();
  }

  std::vector<float> xy;
  std::vector<std::uint32_t> ages;
  for (int f = 0; f < kFrames; ++f) {
    SCOPED_TRACE(testing::Message() << "frame " << f << ", stamp " << a.tiles.now + 1u);
    particles_of_frame(f, domain, &xy, &ages);
    backend->upload(position.data(), xy.data(), position.bytes());
    backend->upload(age.data(), ages.data(), age.bytes());
    ++a.tiles.now;
    backend->run("splat", a);

    // The same particles' deposits added into zeros, with no tile in sight.
    SplatArgs fresh = a;
    fresh.position = xy.data();
    fresh.age = ages.data();
    std::vector<std::uint64_t> expected_units(pixels, 0u);
    for (int slot = 0; slot < kParticles; ++slot)
      splat_particle(fresh, slot, [&](std::size_t p, std::uint64_t u) { expected_units[p] += u; }, [](int) {});
    std::vector<float> expected_film(pixels);
    for (std::size_t p = 0; p < pixels; ++p) expected_film[p] = thickness_from_units(expected_units[p]);

    std::vector<std::uint64_t> got_units(pixels);
    std::vector<float> got_film(pixels);
    backend->download(got_units.data(), units.data(), units.bytes());
    backend->download(got_film.data(), film.data(), film.bytes());
    EXPECT_EQ(got_units, std::vector<std::uint64_t>(pixels, 0u)) << "the sum must be left zero for the next frame";
    EXPECT_EQ(0, std::memcmp(got_film.data(), expected_film.data(), film.bytes()));
    if (c.factor > 0) {
      const BlurArgs& b = a.downsample;
      std::vector<float> expected_low, got_low(low.bytes() / sizeof(float));
      for (int j = 0; j < b.low_height; ++j)
        for (int i = 0; i < b.low_width; ++i)
          expected_low.push_back(
              block_mean_of(b, i, j, [&](int x, int y) { return expected_film[std::size_t(y) * b.width + x]; }));
      backend->download(got_low.data(), low.data(), low.bytes());
      EXPECT_EQ(0, std::memcmp(got_low.data(), expected_low.data(), low.bytes()));
    }
    std::size_t holding = 0;
    for (const std::uint64_t u : expected_units) holding += u != 0;
    if (f == 3) EXPECT_EQ(holding, 0u) << "every particle is dead in frame 3";
    else EXPECT_GT(holding, 20u) << "the frame's blood must reach the panel, or the test shows nothing";
  }
}

// Stamps from 0 (as a stage starts) and across their wrap from 2³² − 1 to 0; each downsample factor,
// whose blocks the panel's 150 × 97 pixels cut short at its edges (but at factor 1).
std::vector<Case> cases() {
  std::vector<Case> all;
  for (const BackendChoice::Want backend : {BackendChoice::Want::cpu, BackendChoice::Want::cuda})
    for (const Case& c : {Case{backend, 0.2f, 0u, 0}, Case{backend, 0.01f, 0u, 2}, Case{backend, 0.2f, 0xfffffffcu, 4},
                          Case{backend, 0.2f, 0u, 1}, Case{backend, 0.2f, 0u, 2}})
      all.push_back(c);
  return all;
}

INSTANTIATE_TEST_SUITE_P(Backends, SplatTiles, testing::ValuesIn(cases()), [](const testing::TestParamInfo<Case>& info) {
  const Case& c = info.param;
  return std::string(c.backend == BackendChoice::Want::cpu ? "cpu" : "cuda") + (c.radius_mm < 0.1f ? "_small" : "") +
         (c.first != 0u ? "_wrapping" : "") + (c.factor > 0 ? "_downsample" + std::to_string(c.factor) : "");
});

}  // namespace
}  // namespace bleedsim