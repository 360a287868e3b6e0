// The spread's settled cuts (core/effects/spread/spread_stage.cpp, SpreadSettle): cuts at the front of the
// list whose stains no longer change are folded once into the light they let through, and a frame
// multiplies in only the live ones. The stain is a product taken cut by cut in the list's order, and
// folding keeps that order and leaves out only factors of exactly 1 (pixels outside a cut's reach),
// so every frame must be, to the bit, the product over every cut made so far (spread_stain). Checked
// on the flat panel and on the turbinate, whose texture stretches a stain's reach 0.6 to 1.7 times,
// with cuts that settle out of order (slow ones hold the front back), at once, or
// stain no pixel centre (a 0.01 mm radius), over and beside one another.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <iostream>
#include <vector>

#include "core/effects/cuts.h"
#include "core/physics/spread.h"
#include "core/simulation/simulation.h"
#include "tests/effects/turbinate_scene.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

// A stroke's worth of cuts, 100 a second for 2 s, zigzagging over the panel and back over itself:
// most full within 0.5 s, every 7th slow (1.25 s: the front waits for it), every 11th at once (1 ms), every 13th
// 0.01 mm across.
void add_stroke(Scene& scene) {
  scene.cuts.clear();
  for (int c = 0; c < 200; ++c) {
    const double s = c / 199.0;
    Cut cut = cut_at(scene, scene.domain.width_mm * (0.1 + 0.8 * (c % 50) / 49.0),
                           scene.domain.height_mm * (0.2 + 0.6 * s + 0.1 * ((c / 5) % 2)), 0.01 * c);
    cut.radius_mm = 1.0 + 0.5 * (c % 3);
    cut.growth_per_s = c % 7 == 3 ? 0.8 : c % 11 == 0 ? 1000.0 : 2.0;
    if (c % 13 == 0) cut.radius_mm = 0.01;  // within a pixel's centre or not at all
    scene.cuts.push_back(cut);
  }
  scene.duration_s = 3.0;
}

// Every frame's stain against the product over every cut whose stain has begun, pixel by pixel.
void expect_every_cut_in_every_frame(const Scene& scene, const SurfaceMap& surface) {
  Simulation sim(scene, BackendChoice{BackendChoice::Want::cpu, 2});
  const PixelGrid grid = scene.domain.grid();
  std::vector<float> got(std::size_t(grid.width) * grid.height);
  for (int k = 0; k < scene.frame_count(); ++k) {
    const double t = scene.frame_time_s(k);
    sim.step();
    sim.copy_field("spread/stain", got.data());
    std::vector<SpreadCut> begun;
    for (const Cut& cut : scene.cuts) {
      const float amplitude = cut_amplitude(cut.start_s, cut.growth_per_s, t);
      if (amplitude > 0.0f)
        begun.push_back({float(cut.x_mm), float(cut.y_mm), float(cut.radius_mm), amplitude});
    }
    for (int j = 0; j < grid.height; ++j)
      for (int i = 0; i < grid.width; ++i) {
        const float expected = spread_stain(begun.data(), int(begun.size()), grid, i, j, surface);
        const float value = got[std::size_t(j) * grid.width + i];
        ASSERT_EQ(std::memcmp(&value, &expected, sizeof value), 0)
            << scene.name << ": frame " << k << ", pixel (" << i << ", " << j << "): " << value << " against "
            << expected << " from all " << begun.size() << " begun cuts";
      }
  }
  // The fold ran: a launch a frame for the stain, and more for the cuts settling.
  const std::uint64_t settles = sim.backend().launches("spread") - std::uint64_t(scene.frame_count());
  std::cout << scene.name << ": " << settles << " launches folded settled cuts in over " << scene.frame_count()
            << " frames\n";
  EXPECT_GT(settles, 10u);  // not a physics bound: that the fold was exercised (27 measured)
}

TEST(SpreadSettle, EveryFrameIsTheProductOverEveryCutOnThePanel) {
  Scene scene = test::scene_in_code(true);
  add_stroke(scene);
  expect_every_cut_in_every_frame(scene, {});
}

TEST(SpreadSettle, EveryFrameIsTheProductOverEveryCutOnTheTurbinate) {
  Scene scene = test::scene_in_code(true);
  const SurfaceMaps maps = test::lay_on_turbinate(scene, Domain{160, 64, 40.0, 16.0});
  add_stroke(scene);
  expect_every_cut_in_every_frame(scene, SurfaceMap{maps.frame.data(), maps.gravity.data(), scene.domain.grid()});
}

}  // namespace
}  // namespace bleedsim