// The reference check on a CI-sized study (issue 18's acceptance): a small scene, three levels on
// each knob's ladder (and the reference's refinement past them), four seeds. For the model as it
// ships, refining the reference's time step or resolution moves no metric by more than the seed
// spread beyond its interval, and the reference is accepted; with the resolution's ladder put two
// halvings coarser, the same check refuses the reference and names the knob.
//
// The bound: a knob is to be refined when its refinement moves a metric's ensemble mean by a
// distance D whose 95 % interval lies above the seed spread (the RMS distance between two runs of
// different seeds); D is the noise-corrected distance between ensemble means (unbiased in D²:
// ensemble_stats_test.cpp). A refinement that changes nothing moves the means by noise alone, which
// the correction takes out; a coarse reference moves them by its discretisation error.
//
// Not in this study, and why (docs/accuracy.md, "What the check says of the model"): along
// compression and particle size the shipped model's reference is not accepted on the covered area,
// whose refinement shift is above its seed spread: 2 % of this pool's area from compression 0.02
// to 0.01 (spread about 1 %); 11 % of the default scene's from particle size 1 to 0.5 (spread
// 2.8 %, the full study of docs/accuracy.md), whose differences do not shrink.
#include <gtest/gtest.h>

#include <string>

#include "core/effects/cuts.h"
#include "core/effects/particles/particle_params.h"
#include "core/runtime/tissue.h"
#include "core/study/study.h"
#include "core/study/study_analysis.h"

namespace bleedsim {
namespace {

// A 6 × 4 mm panel at 0.1 mm pixels; a cut 1 mm above the floor bleeds 1 mm³ in 0.5 s, which runs
// down and pools under 2 mm deep (the contact is made for that depth); 1 s, 30 frames.
Scene pool_scene() {
  Scene scene;
  scene.name = "pool";
  scene.domain = Domain{60, 40, 6.0, 4.0};
  scene.duration_s = 1.0;
  scene.frame_rate_hz = 30.0;
  scene.seed = 1;
  scene.tissue = procedural_tissue(60, 40, 1);
  scene.tissue_source = "procedural";
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().design_depth_mm = 2.0;
  Cut cut = cut_at(scene, 3.0, 3.0, 0.0);
  cut.bleed_s = 0.5;
  scene.cuts.push_back(cut);
  return scene;
}

StudyResult study_of(const std::vector<KnobLevels>& knobs) {
  StudySpec spec;
  spec.knobs = knobs;
  spec.backends = {BackendKind::cpu};
  spec.seeds = 4;
  spec.cpu_threads = 2;
  const Study study(pool_scene(), spec);
  return analyse(study, run_all_jobs(study));
}

std::size_t metric(const char* name) {
  for (std::size_t m = 0; m < metrics().size(); ++m)
    if (std::string(metrics()[m].name) == name) return m;
  return 0;
}

TEST(ReferenceCheck, AcceptsTheShippedModelsReference) {
  // The time step from the fewest sub-steps the contact allows (95) up, and the resolution from a
  // quarter up: reference 380 sub-steps at full resolution, refined to 760 and to twice the pixels.
  const Scene scene = pool_scene();
  const double fewest = fewest_stable_substeps(scene);
  ASSERT_EQ(fewest, 95);
  const StudyResult result =
      study_of({{find_knob("substeps"), {fewest, 2 * fewest, 4 * fewest}}, {find_knob("resolution"), {0.25, 0.5, 1}}});
  EXPECT_TRUE(result.check.accepted) << result.check.verdict;
  ASSERT_EQ(result.check.knobs.size(), 2u);
  for (const KnobCheck& k : result.check.knobs) EXPECT_EQ(k.status.rfind("refine", 0), std::string::npos) << k.knob << ": " << k.status;
  // The seeds move the film, the covered area and the pile: those are judged.
  for (const char* name : {"film_mm", "covered_area_mm2", "pile_height_mm"}) EXPECT_TRUE(result.judged[metric(name)]) << name;
  // The time step is converged at the fewest stable sub-steps (docs/particles.md): every difference
  // along its ladder is within the seeds' noise.
  EXPECT_NE(result.ladders[0].per_metric[metric("film_mm")].fit.statement.find("within the seeds' noise"), std::string::npos)
      << result.ladders[0].per_metric[metric("film_mm")].fit.statement;
  EXPECT_EQ(result.check.verdict.rfind("accepted: ", 0), 0u) << result.check.verdict;
}

TEST(ReferenceCheck, RefusesADeliberatelyCoarseReferenceAndNamesTheKnob) {
  // The resolution's ladder two halvings down (1/16, 1/8, 1/4: a reference of 15 × 10 px, refined
  // to 30 × 20): its refinement moves the covered area (measured at each run's own pixels) by more
  // than the seed spread beyond doubt. The time step stays the scene's (the fewest stable).
  const StudyResult result = study_of({{find_knob("resolution"), {0.0625, 0.125, 0.25}}});
  EXPECT_FALSE(result.check.accepted);
  ASSERT_EQ(result.check.knobs.size(), 1u);
  const KnobCheck& resolution = result.check.knobs[0];
  EXPECT_EQ(resolution.status.rfind("refine: its refinement to 0.5 moves ", 0), 0u) << resolution.status;
  const std::size_t area = metric("covered_area_mm2");
  EXPECT_GT(resolution.distance[area].rms.lo, result.seed_spread[area].value);
  EXPECT_NE(result.check.verdict.find("not accepted: refine resolution"), std::string::npos) << result.check.verdict;
}

}  // namespace
}  // namespace bleedsim