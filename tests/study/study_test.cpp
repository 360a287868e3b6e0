// The accuracy study (core/study/study.cpp, core/study/study_knobs.cpp): the knobs change what they say, the
// reference converges on a small scene, a setting the model cannot run is refused and recorded, and
// bad knob values are refused before anything runs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/runtime/input_error.h"
#include "core/effects/particle_model.h"
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

TEST(StudyKnobs, ParticleSizeKeepsTheBloodsVolumeAndFlow) {
  Scene scene = test::scene_in_code(true);
  scene.particles = ParticleParams{};
  const ParticleParams before = *scene.particles;
  const Cut cut_before = scene.cuts[0];
  find_knob("particle_size")->apply(scene, 2.0);
  const ParticleParams& p = *scene.particles;
  EXPECT_DOUBLE_EQ(p.diameter_mm, 2 * before.diameter_mm);
  EXPECT_DOUBLE_EQ(p.particle_volume_mm3, 4 * before.particle_volume_mm3);  // the same film, in a quarter as many
  EXPECT_EQ(p.flow_mm3_per_s_per_mm, before.flow_mm3_per_s_per_mm);       // the same blood a second
  EXPECT_EQ(scene.cuts[0].flow_mm3_per_s_per_mm, cut_before.flow_mm3_per_s_per_mm);
  EXPECT_EQ(p.capacity, before.capacity / 4);
}

TEST(StudyKnobs, SubstepsRefineTheStepAloneFromTheFewestTheContactAllows) {
  Scene scene = test::scene_in_code(true);
  scene.particles = ParticleParams{};  // substeps = 0: the fewest inside the limit
  const int fewest = particle_mechanics(*scene.particles, scene.domain, scene.frame_rate_hz).substeps;
  const Knob& knob = *find_knob("substeps");
  EXPECT_EQ(knob.base(scene), double(fewest));
  EXPECT_EQ(knob.default_sweep(scene), (std::vector<double>{double(fewest), 2.0 * fewest, 4.0 * fewest}));
  Scene fine = scene;
  knob.apply(fine, 2 * fewest);
  EXPECT_EQ(fine.particles->substeps, 2 * fewest);
  // The contact is the same: only the step changed.
  const ParticleMechanics a = particle_mechanics(*scene.particles, scene.domain, scene.frame_rate_hz);
  const ParticleMechanics b = particle_mechanics(*fine.particles, fine.domain, fine.frame_rate_hz);
  EXPECT_EQ(a.stiffness_per_s2, b.stiffness_per_s2);
  EXPECT_EQ(a.damping_per_s, b.damping_per_s);
  EXPECT_DOUBLE_EQ(b.dt_s, a.dt_s / 2);
}

Scene particle_scene() {
  Scene scene = test::scene_in_code(true);
  scene.particles = ParticleParams{};
  return scene;
}

int fewest_substeps(const Scene& scene) {
  return particle_mechanics(*scene.particles, scene.domain, scene.frame_rate_hz).substeps;
}

TEST(StudyRuns, ASettingPastTheStabilityLimitIsARefusedRow) {
  // Half the fewest sub-steps the contact allows is past its stability limit: that row is refused
  // with the model's reason, and the rows inside the limit run.
  const Scene scene = particle_scene();
  const double fewest = fewest_substeps(scene);
  const double half = std::floor(fewest / 2);
  Study study(scene, spec_of({{find_knob("substeps"), {half, fewest, 2 * fewest}}}, 0.1));
  const std::vector<StudyRun> runs = study.run([](long) {});
  const StudyRun& refused = find_run(runs, "substeps", half);
  EXPECT_EQ(refused.status.rfind("refused: particles.substeps: a sub-step of ", 0), 0u) << refused.status;
  EXPECT_NE(refused.status.find("use at least " + std::to_string(int(fewest)) + " sub-steps"), std::string::npos)
      << refused.status;
  EXPECT_TRUE(refused.errors.empty());
  for (const double value : {fewest, 2 * fewest}) EXPECT_EQ(find_run(runs, "substeps", value).status, "ok") << value;
}

TEST(StudyRuns, AnUnrunnableReferenceStopsTheStudy) {
  // With the sub-steps pinned at the fewest the default contact allows, a hundredth of the
  // compression (a hundred times the stiffness, ten times the stiffness' rate) cannot run.
  Scene scene = particle_scene();
  scene.particles->substeps = fewest_substeps(scene);
  const double e = scene.particles->compression;
  Study study(scene, spec_of({{find_knob("compression"), {e / 100, e}}}, 0.1));
  try {
    study.run([](long) {});
    FAIL() << "an unstable reference ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reference: the finest settings (compression 0.0002) cannot run: refused: "
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
