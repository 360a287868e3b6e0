// The accuracy study (core/study/study.cpp, study_analysis.cpp): its settings and ladders, its
// seeds, its jobs (independent of one another and of their order), the analysis' determinism and
// its refusal of records that do not fit, each seed's own value in the results and the files, and
// bad input refused before anything runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/effects/blur/blur_params.h"
#include "core/effects/cuts.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/vessels/vessel_params.h"
#include "core/runtime/input_error.h"
#include "core/simulation/scene_check.h"
#include "core/study/job_record.h"
#include "core/study/study.h"
#include "core/study/study_analysis.h"
#include "core/study/study_metrics.h"
#include "core/study/study_output.h"
#include "core/simulation/simulation.h"
#include "tests/cli/study_files.h"
#include "tests/effects/hard_case_check.h"
#include "tests/runtime/scenes_in_code.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

// The in-code scene (64 × 48 px, 16 × 12 mm) with the spread, the particles and the blur, 0.1 s.
Scene small_scene() {
  Scene scene = test::scene_in_code(true);
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().capacity = 512;
  scene.effects.set(BlurParams{});
  scene.cuts = {cut_at(scene, 8.0, 4.0, 0.0)};
  scene.duration_s = 0.1;
  return scene;
}

StudySpec spec_of(std::vector<KnobLevels> knobs, int seeds = 3) {
  StudySpec spec;
  spec.knobs = std::move(knobs);
  spec.backends = {BackendKind::cpu};
  spec.seeds = seeds;
  spec.cpu_threads = 2;
  return spec;
}

std::string refusal(const Scene& scene, const StudySpec& spec) {
  try {
    Study study(scene, spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(StudySettings, LaddersMeetAtTheReference) {
  // Compression coarse to fine (given in any order) and resolution: the reference is every knob's
  // finest; each ladder's coarser levels run with the other knob at the reference's; each knob is
  // refined once past the reference.
  const Study study(small_scene(), spec_of({{find_knob("resolution"), {1, 0.5}},
                                            {find_knob("compression"), {0.02, 0.08, 0.04}}}));
  EXPECT_EQ(study.reference_description(), "compression 0.02, resolution 1");
  const std::vector<StudySetting>& s = study.settings();
  ASSERT_EQ(s.size(), 7u);
  EXPECT_EQ(s[0].role, "reference");
  EXPECT_EQ(s[1].role, "scene");
  EXPECT_EQ(s[2].knob + " " + std::to_string(s[2].value) + " " + s[2].role, "compression 0.080000 ladder");
  EXPECT_EQ(s[4].knob + " " + std::to_string(s[4].value) + " " + s[4].role, "compression 0.010000 refinement");
  EXPECT_EQ(s[5].knob + " " + std::to_string(s[5].value) + " " + s[5].role, "resolution 0.500000 ladder");
  EXPECT_EQ(s[6].knob + " " + std::to_string(s[6].value) + " " + s[6].role, "resolution 2.000000 refinement");
  const StudyLadder& compression = study.ladders()[0];
  EXPECT_EQ(compression.values, (std::vector<double>{0.08, 0.04, 0.02, 0.01}));
  EXPECT_EQ(compression.settings, (std::vector<std::size_t>{2, 3, 0, 4}));
  EXPECT_TRUE(compression.refined);
  // The coarsest panel any setting draws: half the resolution. Eight snapshots would need eight
  // frames; three frames are all snapshots.
  EXPECT_EQ(study.grid_width(), 32);
  EXPECT_EQ(study.grid_height(), 24);
  EXPECT_EQ(study.snapshot_frames(), (std::vector<int>{0, 1, 2}));
  // A coarser compression level holds the reference's resolution (and time step); the refinement
  // of resolution holds the reference's compression.
  EXPECT_EQ(study.scene_for(2, 0).effects.get<ParticleParams>().compression, 0.08);
  EXPECT_EQ(study.scene_for(2, 0).domain.width_px, 64);
  EXPECT_EQ(study.scene_for(6, 0).domain.width_px, 128);
  EXPECT_EQ(study.scene_for(6, 0).effects.get<ParticleParams>().compression, 0.02);
  EXPECT_EQ(study.scene_for(2, 0).effects.get<ParticleParams>().substeps,
            study.scene_for(0, 0).effects.get<ParticleParams>().substeps);
}

TEST(StudySettings, TheDefaultTimeStepHoldsTheStiffestContactTheStudyRuns) {
  // Every knob at its defaults: the particles' refinement to half the size is the stiffest contact
  // (four times the stiffness, twice the fewest sub-steps); the time step's ladder is its fewest
  // sub-steps and twice that, refined to four times.
  const Scene scene = small_scene();
  Scene stiffest = scene;
  find_knob("particle_size")->apply(stiffest, 0.5);
  const double fewest = fewest_stable_substeps(stiffest);
  const Study study(scene, spec_of({}));
  std::vector<std::string> names;
  for (const StudyLadder& ladder : study.ladders()) names.push_back(ladder.knob->name);
  EXPECT_EQ(names, (std::vector<std::string>{"compression", "substeps", "particle_size", "blur_radius",
                                             "blur_downsample", "resolution"}));
  EXPECT_EQ(study.ladders()[1].values, (std::vector<double>{fewest, 2 * fewest, 4 * fewest}));
  // Every refinement runs at the reference's time step: none is refused by the contact.
  for (std::size_t i = 0; i < study.settings().size(); ++i)
    EXPECT_FALSE(scene_problem(study.scene_for(i, 0))) << i << ": " << scene_problem(study.scene_for(i, 0)).text();
  // blur_downsample's finest is 1: no down- or upsampling, nothing to refine.
  EXPECT_FALSE(study.ladders()[4].refined);
  EXPECT_EQ(study.ladders()[4].not_refined, "exact at 1: nothing to refine");
}

TEST(StudySeeds, MoveThePhysicsAndLeaveTheTissueAlone) {
  Scene scene = small_scene();
  scene.seed = 41;
  scene.tissue = procedural_tissue(64, 48, 41);
  scene.effects.set(VesselParams{});
  scene.vessel_density = procedural_vessel_density(64, 48, 41);
  const Study study(scene, spec_of({{find_knob("resolution"), {0.5, 1}}}, 4));
  for (int i = 0; i < 4; ++i) {
    const Scene run = study.scene_for(0, i);
    EXPECT_EQ(run.seed, 41u + std::uint64_t(i));
    EXPECT_EQ(resolve_particles(run).model.seed, 41u + std::uint64_t(i));
    EXPECT_EQ(run.tissue.rgba, scene.tissue.rgba) << i;
    EXPECT_EQ(run.vessel_density, scene.vessel_density) << i;
    // At half the resolution, the scene's own tissue and vessels drawn again from its own seed.
    const Scene half = study.scene_for(2, i);
    ASSERT_EQ(half.domain.width_px, 32);
    EXPECT_EQ(half.tissue.rgba, procedural_tissue(32, 24, 41).rgba) << i;
    EXPECT_EQ(half.vessel_density, procedural_vessel_density(32, 24, 41)) << i;
  }
}

TEST(StudyBadInput, IsRefusedBeforeAnythingRuns) {
  const Scene scene = small_scene();
  EXPECT_NE(refusal(scene, spec_of({{find_knob("resolution"), {1}}}, 1))
                .find("--seeds: needs at least 2 (got 1): a confidence interval needs two runs"),
            std::string::npos);
  EXPECT_NE(refusal(scene, spec_of({{find_knob("substeps"), {20.5}}}))
                .find("--knob substeps: values of particles.substeps must be a whole number (got 20.5)"),
            std::string::npos);
  EXPECT_NE(refusal(scene, spec_of({{find_knob("resolution"), {-1}}})).find("--knob resolution: values must be positive (got -1)"),
            std::string::npos);
  EXPECT_NE(refusal(scene, spec_of({{find_knob("blur_downsample"), {3}}}))
                .find("--knob blur_downsample: values of blur.downsample must be 1, 2 or 4 (got 3)"),
            std::string::npos);
  EXPECT_NE(refusal(scene, spec_of({{find_knob("resolution"), {1}}, {find_knob("resolution"), {0.5}}}))
                .find("--knob resolution: is given twice"),
            std::string::npos);
  Scene no_blur = scene;
  no_blur.effects.drop<BlurParams>();
  EXPECT_NE(refusal(no_blur, spec_of({{find_knob("blur_radius"), {2}}})).find("--knob blur_radius: this scene has nothing it changes"),
            std::string::npos);
  StudySpec short_run = spec_of({{find_knob("resolution"), {1}}});
  short_run.duration_s = 0.01;
  EXPECT_NE(refusal(scene, short_run).find("--duration-s: 0.01 s is less than one frame at 30 Hz"), std::string::npos);
  // A hundredth of the compression is a hundred times the stiffness: the reference itself cannot
  // run at the scene's time step.
  EXPECT_NE(refusal(scene, spec_of({{find_knob("compression"), {0.0002, 0.02}}}))
                .find("reference: the finest settings (compression 0.0002) cannot run: particles.substeps: a sub-step of"),
            std::string::npos);
}

// Issue 38, item 12: a level given twice was dropped without a word, through the CLI or a spec.
TEST(StudyBadInput, ALevelGivenTwiceIsRefused) {
  EXPECT_NE(refusal(small_scene(), spec_of({{find_knob("particle_size"), {2, 1, 2}}}))
                .find("--knob particle_size: 2 is given twice: give each level once"),
            std::string::npos);
}

// Every job's record, run in the given order of job indices.
std::vector<std::vector<std::uint8_t>> records_in(const Study& study, std::vector<std::size_t> order) {
  std::vector<std::vector<std::uint8_t>> records(study.job_count());
  for (const std::size_t j : order) records[j] = study.run_job(j, study.job(j).backend, 0);
  return records;
}

std::size_t metric_named(const std::string& name) {
  std::size_t m = 0;
  while (metrics()[m].name != name) ++m;
  return m;
}

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(StudyJobs, AreIndependentOfOneAnotherAndOfTheirOrder) {
  // Compression (with a refinement the time step cannot hold: a refused job) and resolution, three
  // seeds: every job run forwards and again backwards gives the same data bytes, and the analysis
  // of the same records writes the same files.
  const Study study(small_scene(), spec_of({{find_knob("compression"), {0.04, 0.02}}, {find_knob("resolution"), {0.5, 1}}}));
  ASSERT_EQ(study.job_count(), study.settings().size() * 3);
  const Study::Job job = study.job(7);
  EXPECT_EQ(job.setting, 2u);
  EXPECT_EQ(job.seed_index, 1);
  std::vector<std::size_t> order(study.job_count());
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
  const std::vector<std::vector<std::uint8_t>> forwards = records_in(study, order);
  std::reverse(order.begin(), order.end());
  const std::vector<std::vector<std::uint8_t>> backwards = records_in(study, order);
  for (std::size_t j = 0; j < forwards.size(); ++j)
    EXPECT_EQ(data_bytes(deserialize(forwards[j])), data_bytes(deserialize(backwards[j]))) << "job " << j;
  EXPECT_GT(study.job_cost(study.settings().size() * 3 - 1), 0.0);

  // The refinement of compression, 0.01, is past the contact's limit at the reference's time step.
  const JobRecord refused = deserialize(forwards[3 * 3]);
  EXPECT_EQ(study.settings()[refused.setting].role, "refinement");
  EXPECT_EQ(refused.status.rfind("refused: particles.substeps: a sub-step of ", 0), 0u) << refused.status;

  const StudyResult result = analyse(study, forwards);
  EXPECT_EQ(result.settings[3].status, refused.status);
  EXPECT_EQ(result.ladders[0].refused.size(), 1u);
  EXPECT_EQ(result.check.knobs[0].status.rfind("not checked: its refinement to 0.01 did not run (refused: ", 0), 0u)
      << result.check.knobs[0].status;
  EXPECT_FALSE(result.check.accepted);
  const std::filesystem::path dir = std::filesystem::path(test::binary_dir()) / "test-scratch" / "StudyJobs";
  std::filesystem::remove_all(dir);
  for (const char* copy : {"a", "b"}) {
    std::filesystem::create_directories(dir / copy);
    write_study_files((dir / copy).string(), study, analyse(study, forwards), {});
  }
  for (const char* name : {"study.csv", "ladders.csv", "study.h5"})
    EXPECT_EQ(file_text(dir / "a" / name), file_text(dir / "b" / name)) << name;
}

// The rest time the study reports for each seed is the one the seed's own run gives, read here from
// the simulation frame by frame (the live slots' speeds in double): the end of the last frame in
// which one moved faster than 0.1 mm/s. A cut bleeding 0.2 s on the small scene's tilted panel,
// 1 s: its blood runs, and stops (the sleep of docs/particles.md#rest) before the end.
TEST(StudyRest, IsTheEndOfTheLastFrameInWhichALiveParticleMovedFasterThanTheRestSpeed) {
  Scene scene = small_scene();
  scene.cuts.front().bleed_s = 0.2;
  scene.duration_s = 1.0;
  const Study study(scene, spec_of({}, 2));
  const StudyResult result = analyse(study, run_all_jobs(study));
  const std::size_t rest = metric_named("rest_s");
  std::vector<double> direct;
  for (int seed = 0; seed < 2; ++seed) {
    const Scene run = study.scene_for(0, seed);
    const ParticleModel m = resolve_particles(run).model;
    Simulation sim(run, BackendChoice{BackendChoice::Want::cpu, 2});
    double rested = 0;
    while (sim.frames_done() < run.frame_count()) {
      sim.step();
      const test::Particles p(sim);
      for (int s = 0; s < p.slots(); ++s)
        if (is_alive(m, p.age[s]) && p.speed(s) > 0.1) rested = sim.time_s();
    }
    direct.push_back(rested);
  }
  std::cout << "rest at " << direct[0] << " s and " << direct[1] << " s" << std::endl;
  EXPECT_GT(std::min(direct[0], direct[1]), 0.0) << "the blood never moved: the test says nothing";
  EXPECT_LT(std::max(direct[0], direct[1]), scene.duration_s) << "the blood never rested: the test says nothing";
  EXPECT_NEAR(result.settings[0].value[rest].value, 0.5 * (direct[0] + direct[1]), 1e-12);
  ASSERT_EQ(result.settings[0].per_seed[rest].size(), 2u);
  for (int seed = 0; seed < 2; ++seed)
    EXPECT_NEAR(result.settings[0].per_seed[rest][seed], direct[seed], 1e-12) << "seed " << seed;
}

// A study of three settings and three seeds whose records are made to rest at different times
// (0.1 s runs never rest): seed s's fastest particle moves in frames 0 to s only, so its rest time
// is s + 1 frames, and a list of the seeds in any other order, or their mean, is told apart.
struct SeedsRestingApart {
  Study study{small_scene(), spec_of({{find_knob("resolution"), {1}}})};
  std::vector<std::vector<std::uint8_t>> records = resting_apart(run_all_jobs(study));

  static std::vector<std::vector<std::uint8_t>> resting_apart(std::vector<std::vector<std::uint8_t>> records) {
    for (std::vector<std::uint8_t>& bytes : records) {
      JobRecord r = deserialize(bytes);
      for (std::size_t k = 0; k < r.fastest_mm_s.size(); ++k) r.fastest_mm_s[k] = k <= r.seed_index ? 1.0 : 0.0;
      bytes = serialize(r);
    }
    return records;
  }
};

// The analysis' mean: summed in seed order, then divided (ensemble_stats.cpp, mean_ci), so the
// same values give the same bits.
double mean_in_order(const std::vector<double>& values) {
  double sum = 0;
  for (const double v : values) sum += v;
  return sum / double(values.size());
}

TEST(StudyAnalysis, KeepsEachSeedsOwnValueInSeedOrder) {
  const SeedsRestingApart fixture;
  const Study& study = fixture.study;
  const StudyResult result = analyse(study, fixture.records);
  const std::size_t film = metric_named("film_mm"), rest = metric_named("rest_s");
  // The scene has every metric: each setting's value of each is the mean of its seeds' values, to
  // the bit.
  for (const SettingResult& s : result.settings) {
    ASSERT_EQ(s.status, "ok");
    for (std::size_t m = 0; m < metrics().size(); ++m) {
      ASSERT_EQ(s.per_seed[m].size(), 3u) << metrics()[m].name;
      EXPECT_EQ(s.value[m].value, mean_in_order(s.per_seed[m])) << metrics()[m].name;
    }
  }
  // Each seed's value is what its own record gives: the rest time of its fastest particle's
  // speeds, the film's mean over the snapshots' cells.
  const double frame_s = 1.0 / study.scene().frame_rate_hz;
  for (std::size_t j = 0; j < study.job_count(); ++j) {
    const JobRecord r = deserialize(fixture.records[j]);
    const SettingResult& s = result.settings[r.setting];
    EXPECT_EQ(s.per_seed[rest].at(r.seed_index), rest_time_s(r.fastest_mm_s, frame_s)) << "job " << j;
    EXPECT_EQ(s.per_seed[film].at(r.seed_index), mean_in_order(std::vector<double>(r.film_mm.begin(), r.film_mm.end())))
        << "job " << j;
  }
  // The seeds differ (else their order could not show), in the rest time as made and in the film.
  const SettingResult& reference = result.settings[0];
  EXPECT_EQ(reference.per_seed[rest], (std::vector<double>{frame_s, 2 * frame_s, 3 * frame_s}));
  EXPECT_NE(reference.per_seed[film].front(), reference.per_seed[film].back());
}

// study.h5 holds each seed's value of every metric (the scene has them all) as `<metric>_per_seed`
// with the metric's unit; study.csv's last column is the latest seed's rest time (3 frames: 0.1 s,
// where the first seed's is 0.0333 and the mean 0.0667), empty on the noise floor's row.
TEST(StudyFiles, HoldEachSeedsOwnValueAndTheLatestRest) {
  const SeedsRestingApart fixture;
  const StudyResult result = analyse(fixture.study, fixture.records);
  const std::filesystem::path dir = test::test_output_folder("study");
  write_study_files(dir.string(), fixture.study, result, {});
  const test::File file(dir / "study.h5");
  for (std::size_t i = 0; i < result.settings.size(); ++i)
    for (std::size_t m = 0; m < metrics().size(); ++m) {
      char group[32];
      std::snprintf(group, sizeof group, "settings/%03zu/", i);
      const std::string name = group + std::string(metrics()[m].name) + "_per_seed";
      const test::Dataset seeds(file, name);
      EXPECT_EQ(test::dims_of(seeds), std::vector<hsize_t>{3}) << name;
      EXPECT_EQ(test::read_all<double>(seeds, H5T_NATIVE_DOUBLE), result.settings[i].per_seed[m]) << name;
      EXPECT_EQ(test::text_attribute(seeds, "unit").value, metrics()[m].unit) << name;
    }
  const std::vector<std::string> csv = test::lines_of(file_text(dir / "study.csv"));
  ASSERT_EQ(csv.size(), result.settings.size() + 2);  // the header, each setting, the noise floor
  EXPECT_EQ(test::fields_of(csv.front()).back(), "rest_s_latest_seed");
  for (std::size_t row = 1; row + 1 < csv.size(); ++row) EXPECT_EQ(test::fields_of(csv[row]).back(), "0.1") << csv[row];
  EXPECT_EQ(test::fields_of(csv.back()).back(), "") << csv.back();
}

std::string analysis_refusal(const Study& study, const std::vector<std::vector<std::uint8_t>>& records) {
  try {
    analyse(study, records);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(StudyAnalysis, RefusesRecordsThatDoNotFit) {
  const Study study(small_scene(), spec_of({{find_knob("resolution"), {1}}}));
  std::vector<std::size_t> all(study.job_count());
  for (std::size_t j = 0; j < all.size(); ++j) all[j] = j;
  const std::vector<std::vector<std::uint8_t>> records = records_in(study, all);
  std::vector<std::vector<std::uint8_t>> fewer(records.begin(), records.end() - 1);
  EXPECT_NE(analysis_refusal(study, fewer).find("has 9 jobs, and 8 records were given"), std::string::npos)
      << analysis_refusal(study, fewer);
  std::vector<std::vector<std::uint8_t>> swapped = records;
  std::swap(swapped[1], swapped[2]);
  EXPECT_NE(analysis_refusal(study, swapped).find("record 1 is job 2: the records must come in job order"), std::string::npos);
  const Study other(small_scene(), spec_of({{find_knob("resolution"), {1}}}, 4));
  EXPECT_NE(analysis_refusal(other, std::vector<std::vector<std::uint8_t>>(records.begin(), records.end()))
                .find("jobs, and 9 records"),
            std::string::npos);
  std::vector<std::vector<std::uint8_t>> foreign(other.job_count(), records[0]);
  EXPECT_NE(analysis_refusal(other, foreign).find("record 0 was made by another study"), std::string::npos);
  std::vector<std::vector<std::uint8_t>> garbled = records;
  garbled[4].resize(20);
  EXPECT_NE(analysis_refusal(study, garbled).find("record 4: job record: truncated"), std::string::npos);
}

TEST(StudyAnalysis, RefusesBackendsThatDisagree) {
  // The same job on two "backends" (both the CPU here): one cell of one run's film moved by an ulp.
  StudySpec spec = spec_of({{find_knob("resolution"), {1}}});
  spec.backends = {BackendKind::cpu, BackendKind::cpu};
  const Study study(small_scene(), spec);
  std::vector<std::size_t> all(study.job_count());
  for (std::size_t j = 0; j < all.size(); ++j) all[j] = j;
  std::vector<std::vector<std::uint8_t>> records = records_in(study, all);
  EXPECT_EQ(analysis_refusal(study, records), "");
  JobRecord r = deserialize(records[5]);
  r.film_mm[10] = std::nextafter(r.film_mm[10], 1.0f);
  records[5] = serialize(r);
  EXPECT_NE(analysis_refusal(study, records).find("job 5 (reference, seed 2) gives other data on cpu than on cpu"),
            std::string::npos)
      << analysis_refusal(study, records);
}

}  // namespace
}  // namespace bleedsim