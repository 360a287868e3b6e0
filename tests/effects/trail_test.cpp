// Trails (core/physics/trail.h): where blood has run the tissue keeps a residue that dries as
// exp(−t / drying_s), against that closed form; and only a scene with [trail] pays for it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/effects/blend/blend_stage.h"
#include "core/effects/blend/optics_params.h"
#include "core/effects/cuts.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/trail/trail_params.h"
#include "core/effects/trail/trail_stage.h"
#include "core/physics/optics_tables.h"
#include "core/physics/pixel_kernels.h"
#include "core/runtime/tissue.h"
#include "core/simulation/simulation.h"
#include "tests/runtime/field_values.h"

namespace bleedsim {
namespace {

const BackendChoice kCpu{BackendChoice::Want::cpu, 2};

// One pixel under a film of h for a few frames, then bare: its residue is residue·h (the most the
// film left), then that times decay per frame. decay is exp(−1/(f·τ)) rounded once to float (2⁻²⁴
// relative) and each frame's product rounds once more: after n frames the residue is within
// n·2⁻²³ of residue·h·exp(−n/(f·τ)), relative.
TEST(TrailPixel, TheResidueDriesAsTheClosedFormSays) {
  TrailParams trail;
  trail.residue = 0.1;
  trail.drying_s = 2.0;
  const double fps = 30.0;
  float film = 0.12f, residue = 0.0f;
  const TrailPixel pixel{&film, &residue, float(trail.residue), trail_decay_per_frame(trail, fps), PixelGrid{1, 1}};
  for (int k = 0; k < 5; ++k) pixel(0, 0);
  EXPECT_EQ(residue, 0.1f * 0.12f);
  film = 0.0f;
  const double left = residue;
  for (int n = 1; n <= 300; ++n) {
    pixel(0, 0);
    const double closed = left * std::exp(-n / (fps * trail.drying_s));
    EXPECT_NEAR(residue, closed, n * std::ldexp(closed, -23)) << n;
  }
}

// A thin film passing over a pixel that already holds a residue leaves the larger of the two: a
// trail is not thickened by blood passing again, nor erased by a thinner stream.
TEST(TrailPixel, KeepsTheLargerOfTheDriedResidueAndTheFilmsShare) {
  float film = 0.01f, residue = 0.05f;
  const TrailPixel pixel{&film, &residue, 0.5f, 0.9f, PixelGrid{1, 1}};
  pixel(0, 0);
  EXPECT_EQ(residue, 0.05f * 0.9f);  // 0.045 > 0.5 · 0.01
  film = 0.2f;
  pixel(0, 0);
  EXPECT_EQ(residue, 0.5f * 0.2f);
}

// A drop slides down a mucosa without grip (pinning and yield 0) from a cut near the top: once it
// has passed a pixel of its path, that pixel holds a residue (> 0) that dries by exactly one
// frame's decay a frame, and after n frames is within n·2⁻²³ of exp(−n/(f·τ)) of what it was.
TEST(TrailStage, WhereADropHasRunTheResidueDries) {
  Scene scene;
  scene.name = "trail";
  scene.domain = Domain{40, 240, 2.0, 12.0};
  scene.duration_s = 3.0;
  scene.tissue = procedural_tissue(40, 240, 3);
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().pinning_mm3_s2 = scene.effects.get<ParticleParams>().yield_mm2_s2 = 0.0;
  scene.effects.get<ParticleParams>().capacity = 1024;
  scene.effects.set(TrailParams{});
  scene.effects.get<TrailParams>().drying_s = 1.5;
  Cut cut = cut_at(scene, 1.0, 1.5, 0.0);
  cut.bleed_s = 0.2;
  scene.cuts.push_back(cut);
  Simulation sim(scene, kCpu);
  const float decay = trail_decay_per_frame(scene.effects.get<TrailParams>(), scene.frame_rate_hz);
  // The path's middle, 6 mm down: pixel (20, 120). Frame by frame: covered, then bare for good.
  const std::size_t p = 120 * 40 + 20;
  std::vector<float> film, residue;
  while (sim.frames_done() < scene.frame_count()) {
    sim.step();
    film.push_back(test::field_values<float>(sim, "splat/thickness")[p]);
    residue.push_back(test::field_values<float>(sim, "trail/residue")[p]);
  }
  std::size_t last_covered = 0;
  for (std::size_t k = 0; k < film.size(); ++k)
    if (film[k] > 0.0f) last_covered = k;
  ASSERT_GT(last_covered, 0u) << "the drop never reached the pixel";
  ASSERT_LT(last_covered + 30, film.size()) << "the drop had not passed a second before the end";
  EXPECT_GT(residue[last_covered], 0.0f);
  for (std::size_t k = last_covered + 1; k < film.size(); ++k) {
    EXPECT_EQ(residue[k], residue[k - 1] * decay) << k;
    const double n = double(k - last_covered);
    const double closed =
        residue[last_covered] * std::exp(-n / (scene.frame_rate_hz * scene.effects.get<TrailParams>().drying_s));
    EXPECT_NEAR(residue[k], closed, n * std::ldexp(closed, -23)) << k;
  }
}

// The blend stage runs the trail in its own pass (TrailThenBlend): pixel by pixel, the trail and
// then the blend. It must leave the residue and the frame as the two passes one after the other
// do, to the byte: the blend reads the residue only at its own pixel. The panel has bare tissue,
// film over old residue and over none, a stain, and the suction's path through it, lit.
TEST(TrailThenBlend, GivesTheBytesOfTheTrailsPassThenTheBlends) {
  const int w = 48, h = 32;
  const std::size_t n = std::size_t(w) * h;
  Scene scene;
  scene.domain = Domain{w, h, 4.8, 3.2};
  scene.effects.set(OpticsParams{});
  scene.effects.get<OpticsParams>().falloff = true;
  scene.effects.set(TrailParams{});
  const Image tissue = procedural_tissue(w, h, 5);
  const std::vector<float> tables = optics_tables();
  std::vector<float> film(n), stain(n), residue(n);
  for (std::size_t p = 0; p < n; ++p) {
    const int i = int(p % w), j = int(p / w);
    film[p] = i > 8 && i < 30 ? 0.004f * float((i * 7 + j * 3) % 11) : 0.0f;
    stain[p] = j > 20 ? 0.3f : 0.0f;
    residue[p] = (i + j) % 3 == 0 ? 0.002f * float(j % 5) : 0.0f;
  }
  const std::vector<float> path{0.5f, 1.0f, 2.5f, 1.6f};  // one segment of the suction's path, mm
  struct Result {
    std::vector<float> residue;
    std::vector<std::uint8_t> frame;
  } apart{residue, std::vector<std::uint8_t>(4 * n)}, together = apart;
  for (Result* r : {&apart, &together}) {
    TrailPixel trail{film.data(), r->residue.data(), float(scene.effects.get<TrailParams>().residue),
                     trail_decay_per_frame(scene.effects.get<TrailParams>(), scene.frame_rate_hz), scene.domain.grid()};
    sweep_trail(trail, path.data(), path, 1, 0.4);
    const BlendPixel blend = blend_work(scene, tables.data(), tissue.rgba.data(), stain.data(), film.data(),
                                        r->residue.data(), r->frame.data());
    if (r == &apart) {
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) trail(i, j);
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) blend(i, j);
    } else {
      const TrailThenBlend pass = pair_pixels(trail, blend);
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) pass(i, j);
    }
  }
  EXPECT_EQ(together.residue, apart.residue);
  EXPECT_EQ(together.frame, apart.frame);
  // Not trivially: the trail changed residues (wetted, dried and sucked dry), and they show.
  EXPECT_NE(apart.residue, residue);
  EXPECT_EQ(apart.residue[std::size_t(13) * w + 15], 0.0f);  // (1.55, 1.35) mm: on the path
  EXPECT_GT(apart.residue[std::size_t(25) * w + 20], 0.0f);
}

TEST(TrailThenBlend, RefusesPassesOverDifferentPixels) {
  float film = 0.0f, residue = 0.0f;
  const TrailPixel trail{&film, &residue, 0.5f, 0.9f, PixelGrid{1, 1}};
  BlendPixel blend{};
  blend.grid = PixelGrid{2, 1};
  EXPECT_THROW(pair_pixels(trail, blend), std::logic_error);
}

// Only a scene with [trail] runs the trail stage and holds its field.
TEST(TrailStage, ASceneWithoutTrailsHasNoneOfTheirCost) {
  Scene scene;
  scene.domain = Domain{16, 16, 4.0, 4.0};
  scene.tissue = procedural_tissue(16, 16, 1);
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().capacity = 64;
  Simulation without(scene, kCpu);
  scene.effects.set(TrailParams{});
  Simulation with(scene, kCpu);
  for (int k = 0; k < 3; ++k) without.step(), with.step();
  EXPECT_EQ(without.backend().launches("trail"), 0u);
  EXPECT_EQ(with.backend().launches("trail"), 3u);
  EXPECT_EQ(with.backend().bytes_in_use() - without.backend().bytes_in_use(), 16u * 16 * sizeof(float));
}

}  // namespace
}  // namespace bleedsim