// The accuracy study (core/study/study.cpp, core/study/study_knobs.cpp): the knobs change what they say, the
// reference converges on a small scene, a setting the model cannot run is refused and recorded, and
// bad knob values are refused before anything runs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/runtime/input_error.h"
#include "core/study/study.h"
#include "core/study/study_output.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

const StudyRun& find_run(const std::vector<StudyRun>& runs, const std::string& knob, double value) {
  for (const StudyRun& run : runs)
    if (run.setting.knob == knob && (run.setting.role.rfind("reference", 0) == 0 || run.setting.value == value)) return run;
  throw std::out_of_range(knob);
}

StudySpec spec_of(std::vector<KnobSweep> sweeps, double duration_s) {
  StudySpec spec;
  spec.sweeps = std::move(sweeps);
  spec.backends = {BackendKind::cpu};
  spec.duration_s = duration_s;
  return spec;
}

TEST(StudyReference, TheSpreadConvergesWithResolution) {
  // The in-code spread scene (64 × 48 px, one cut) at ¼, ½, 1 and 2 × its resolution, compared on
  // the coarsest grid (16 × 12 cells) with the reference (2 ×) and its check (4 ×). The error falls
  // with every doubling, and the reference's own (its check's) is far below every error reported.
  Study study(test::scene_in_code(true), spec_of({{find_knob("resolution"), {0.25, 0.5, 1.0, 2.0}}}, 1.0));
  EXPECT_EQ(study.grid_width(), 16);
  EXPECT_EQ(study.grid_height(), 12);
  const std::vector<StudyRun> runs = study.run([](long) {});
  const auto error = [&](const char* knob, double value) { return summarize(find_run(runs, knob, value)).mean.stain_l1; };
  EXPECT_EQ(error("reference", 0), 0.0);
  EXPECT_EQ(error("resolution", 2.0), 0.0);  // the finest setting is the reference
  EXPECT_GT(error("resolution", 0.25), error("resolution", 0.5));
  EXPECT_GT(error("resolution", 0.5), error("resolution", 1.0));
  EXPECT_GT(error("resolution", 1.0), 0.0);
  EXPECT_LT(error("reference_check", 0), 0.2 * error("resolution", 1.0))
      << "the reference is not converged: doubling its resolution moves it by " << error("reference_check", 0);
}

TEST(StudyKnobs, ParticleSizeKeepsTheBloodsVolume) {
  Scene scene = test::scene_in_code(true);
  scene.particles = ParticleParams{};
  scene.cuts[0].rate_per_s = 500;
  const ParticleParams before = *scene.particles;
  find_knob("particle_size")->apply(scene, 2.0);
  const ParticleParams& p = *scene.particles;
  EXPECT_DOUBLE_EQ(p.diameter_mm, 2 * before.diameter_mm);
  EXPECT_DOUBLE_EQ(p.rate_per_s * p.particle_volume_mm3, before.rate_per_s * before.particle_volume_mm3);
  EXPECT_DOUBLE_EQ(scene.cuts[0].rate_per_s, 125.0);
  EXPECT_EQ(p.capacity, before.capacity / 4);
}

TEST(StudyKnobs, FewerSubstepsSoftenTheContactMoreRefineTheStepAlone) {
  Scene scene = test::scene_in_code(true);
  scene.particles = ParticleParams{};  // 40 sub-steps, k = 4e5, c = 100
  Scene coarse = scene, fine = scene;
  find_knob("substeps")->apply(coarse, 20);
  EXPECT_EQ(coarse.particles->substeps, 20);
  EXPECT_DOUBLE_EQ(coarse.particles->stiffness_per_s2, 1e5);  // k·dt² kept
  EXPECT_DOUBLE_EQ(coarse.particles->damping_per_s, 50);       // c·dt kept
  find_knob("substeps")->apply(fine, 80);
  EXPECT_EQ(fine.particles->substeps, 80);
  EXPECT_DOUBLE_EQ(fine.particles->stiffness_per_s2, 4e5);
}

Scene particle_scene() {
  Scene scene = test::scene_in_code(true);
  scene.particles = ParticleParams{};  // 40 sub-steps; k = 4e5/s², stable below 0.92 ms
  return scene;
}

TEST(StudyRuns, ASettingPastTheStabilityLimitIsARefusedRow) {
  // The reference (k = 4e6, 400 sub-steps of 0.083 ms) is stable; k = 4e6 at the base's 40
  // sub-steps (0.83 ms) is not, and is recorded as refused with the model's reason.
  Study study(particle_scene(), spec_of({{find_knob("stiffness"), {4e5, 4e6}}, {find_knob("substeps"), {40, 400}}}, 0.1));
  const std::vector<StudyRun> runs = study.run([](long) {});
  EXPECT_EQ(find_run(runs, "stiffness", 4e6).status.rfind("refused: particles.substeps: a sub-step of 0.8333 ms is past", 0), 0u)
      << find_run(runs, "stiffness", 4e6).status;
  EXPECT_TRUE(find_run(runs, "stiffness", 4e6).errors.empty());
  for (const auto& [knob, value] : {std::pair<const char*, double>{"stiffness", 4e5}, {"substeps", 40}, {"substeps", 400}})
    EXPECT_EQ(find_run(runs, knob, value).status, "ok") << knob << " " << value;
}

TEST(StudyRuns, AnUnrunnableReferenceStopsTheStudy) {
  Study study(particle_scene(), spec_of({{find_knob("stiffness"), {4e5, 4e7}}}, 0.1));
  try {
    study.run([](long) {});
    FAIL() << "an unstable reference ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reference: the finest settings (stiffness 4e+07) cannot run: refused: "
                                         "particles.substeps"),
              std::string::npos)
        << e.what();
  }
}

TEST(StudyBadInput, KnobValuesAreCheckedBeforeAnythingRuns) {
  Scene scene = test::scene_in_code(true);
  scene.particles = ParticleParams{};
  const auto refusal = [&](const char* knob, std::vector<double> values) {
    try {
      Study(scene, spec_of({{find_knob(knob), std::move(values)}}, 0.1));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refusal("substeps", {20.5}).find("--knob substeps: values of particles.substeps must be a whole number (got 20.5)"), std::string::npos);
  EXPECT_NE(refusal("resolution", {-1}).find("--knob resolution: values must be positive (got -1)"), std::string::npos);
  EXPECT_NE(refusal("blur_radius", {2}).find("--knob blur_radius: this scene has nothing it changes"), std::string::npos);
  scene.blur = BlurParams{};
  EXPECT_NE(refusal("blur_downsample", {3}).find("--knob blur_downsample: values of blur.downsample must be 1, 2 or 4 (got 3)"),
            std::string::npos);
  EXPECT_EQ(find_knob("nothing"), nullptr);
  try {
    Study(scene, spec_of({{find_knob("substeps"), {40}}}, 0.01));
    FAIL() << "a study of no frames was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--duration-s: 0.01 s is less than one frame at 30 Hz"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace bleedsim
