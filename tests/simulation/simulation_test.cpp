// The embedding API (core/simulation/simulation.h) without the CLI: a host builds a scene in code, feeds cut
// events, steps, and reads frames and fields.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/effects/blend/blend_stage.h"
#include "core/effects/blend/optics_params.h"
#include "core/effects/cuts.h"
#include "core/physics/optics_tables.h"
#include "core/simulation/simulation.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

const BackendChoice kCpu{BackendChoice::Want::cpu, 2};

float stain_at(const Simulation& sim, int i, int j) {
  const std::vector<std::uint8_t> bytes = sim.copy_field("spread/stain");
  float value;
  std::memcpy(&value, bytes.data() + 4 * (std::size_t(j) * 64 + i), 4);
  return value;
}

TEST(Simulation, StepsFrameByFrameAtTheSceneRate) {
  Simulation sim(test::scene_in_code(true), kCpu);
  EXPECT_EQ(sim.frames_done(), 0);
  EXPECT_EQ(sim.time_s(), 0.0);
  sim.step();
  sim.step();
  EXPECT_EQ(sim.frames_done(), 2);
  EXPECT_DOUBLE_EQ(sim.time_s(), 2.0 / 30.0);
}

TEST(Simulation, TheStainAtACutsCentreIsItsAmplitude) {
  // The cut sits on the centre of pixel (32, 24), so the profile there is exactly 1 and the stain
  // is the amplitude (up to the rounding of 1 − (1 − a)): growth 1.5/s from t = 0 gives 1.5 · t
  // until it is full.
  Simulation sim(test::scene_in_code(true), kCpu);
  for (int k = 1; k <= 30; ++k) {
    sim.step();
    const double t = k / 30.0;
    EXPECT_NEAR(stain_at(sim, 32, 24), std::min(1.0, 1.5 * t), 1e-7) << "frame " << k - 1;
  }
}

TEST(Simulation, ACutFedAtRunTimeStainsFromItsStartOn) {
  Simulation sim(test::scene_in_code(true), kCpu);
  const Scene& scene = sim.scene();
  // The centre of pixel (8, 8): (8.5 · 0.25, 8.5 · 0.25) mm, far from the scene's own cut.
  sim.add_cut(cut_at(scene, 2.125, 2.125, 0.2));
  ASSERT_EQ(sim.cuts().size(), 2u);
  for (int k = 0; k < 6; ++k) sim.step();  // t = 0.2: starts now, amplitude 0
  EXPECT_EQ(stain_at(sim, 8, 8), 0.0f);
  for (int k = 0; k < 6; ++k) sim.step();  // t = 0.4: 0.2 s · 1.5/s
  EXPECT_NEAR(stain_at(sim, 8, 8), 0.3f, 1e-6f);
}

// A full stain is drawn as stain_depth_mm of blood in the tissue: in linear light each channel keeps
// exp(−2·μ_c·depth) of the tissue's (docs/optics.md); far from the cut the tissue keeps its bytes.
TEST(Simulation, TheFrameIsTheTissueUnderTheStainAsBlood) {
  const Scene scene = test::scene_in_code(true);
  Simulation sim(scene, kCpu);
  for (int k = 0; k < 30; ++k) sim.step();
  const std::vector<std::uint8_t> frame = sim.copy_field("frame");
  ASSERT_EQ(frame.size(), 64u * 48 * 4);
  const std::size_t centre = 4 * (24 * 64 + 32), corner = 0;
  const std::vector<float> tables = optics_tables();
  const SrgbTables srgb = srgb_tables(tables.data());
  const BloodOptics blood = blood_optics(OpticsParams{});
  for (int c = 0; c < 3; ++c) {
    const double light = linear_from_srgb(srgb, scene.tissue.rgba[centre + c]) *
                         std::exp(-2.0 * blood.absorption_per_mm[c] * blood.stain_depth_mm);
    EXPECT_NEAR(frame[centre + c], srgb_from_linear(srgb, float(light)), 1) << c;  // the table's interpolation
  }
  EXPECT_LT(frame[centre + 1], scene.tissue.rgba[centre + 1]);  // the stain reads red: green and blue taken
  EXPECT_EQ(frame[centre + 3], scene.tissue.rgba[centre + 3]);
  EXPECT_EQ(std::memcmp(&frame[corner], &scene.tissue.rgba[corner], 4), 0);  // far away: tissue
}

TEST(Simulation, GivesFieldsInPlaceOnTheBackend) {
  Simulation sim(test::scene_in_code(true), kCpu);
  sim.step();
  const FieldView view = sim.field("spread/stain");
  EXPECT_EQ(view.location, BackendKind::cpu);
  ASSERT_NE(view.data, nullptr);
  EXPECT_EQ(view.field->width, 64);
  EXPECT_EQ(view.field->height, 48);
  EXPECT_EQ(view.field->bytes(), 64u * 48 * 4);
  EXPECT_EQ(std::memcmp(view.data, sim.copy_field("spread/stain").data(), view.field->bytes()), 0);
}

TEST(Simulation, RefusesBadCutsAndUnknownFields) {
  Simulation sim(test::scene_in_code(true), kCpu);
  Cut cut = cut_at(sim.scene(), 1.0, 1.0, 0.0);
  cut.radius_mm = 0.0;
  EXPECT_THROW(sim.add_cut(cut), std::invalid_argument);
  cut.radius_mm = NAN;
  EXPECT_THROW(sim.add_cut(cut), std::invalid_argument);
  EXPECT_THROW(sim.field("blood"), std::out_of_range);
}

TEST(Simulation, RefusesASceneWithNoFramesOrTooManyForItsFrameCounter) {
  Scene scene = test::scene_in_code(true);
  scene.duration_s = 0.001;  // rounds to 0 frames at 30 Hz
  EXPECT_THROW(Simulation(scene, kCpu), std::invalid_argument);
  scene.duration_s = 1e9;  // 3·10^10 frames would overflow frame_count()
  EXPECT_THROW(Simulation(scene, kCpu), std::invalid_argument);
}

TEST(Simulation, RefusesASceneWhoseTissueDoesNotMatchItsDomain) {
  Scene scene = test::scene_in_code(true);
  scene.tissue.rgba.resize(10);
  EXPECT_THROW(Simulation(scene, kCpu), std::invalid_argument);
}

}  // namespace
}  // namespace bleedsim