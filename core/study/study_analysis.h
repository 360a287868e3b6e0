#pragma once
// The accuracy study's analysis (docs/accuracy.md): every comparison between runs, from the job
// records alone. Deterministic: the same records give the same results, bit for bit, whatever
// ran them where (timings aside).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/study/ensemble_stats.h"
#include "core/study/ladder.h"
#include "core/study/study.h"

namespace bleedsim {

// The distribution metrics, each a list of components per run: a curve over the frames, a field
// over the grid's cells at the snapshot frames, or a profile over its columns at them.
enum class Metric { film, stain, front, covered_area, volume, pile_height, rest };
struct MetricInfo {
  Metric metric;
  const char* name;  // as the files call it
  const char* unit;
  const char* what;
};
const std::vector<MetricInfo>& metrics();

// A setting's compute per frame on one backend: nearest-rank percentiles over every frame of every
// seed's run, and the lowest and highest of the seeds' own medians.
struct SettingTiming {
  BackendKind backend = BackendKind::cpu;
  std::string device;
  double ms_p50 = kNaN, ms_p99 = kNaN, ms_p50_low = kNaN, ms_p50_high = kNaN;
  std::vector<std::vector<double>> frame_seconds;  // per seed, every frame
};

// One run against another at the snapshot frames (core/study/study_metrics.h, RunDistance): film
// L1 and RMS, the colour's mean squared difference and its PSNR, the stain's L1.
struct RunDistances {
  Estimate film_l1_mm, film_l2_mm, frame_mse, frame_psnr_db, stain_l1;
};

struct SettingResult {
  StudySetting setting;
  std::string status = "ok";          // or the refusal of its first refused run
  // Per metric (in metrics()' order; NaN where the scene lacks it): the mean over its components
  // in each seed, mean and interval over the seeds; and the distance of the ensemble mean from the
  // reference's, the seeds' noise taken out.
  std::vector<Estimate> value;
  std::vector<Distance> distance;
  // Per metric, each seed's value (its mean over the components) in seed order, whose mean is
  // `value`; empty where the metric is absent or the setting did not run. The worst seed, which the
  // mean hides, matters too: issue 36 asks that every seed come to rest in time.
  std::vector<std::vector<double>> per_seed;
  // Each seed's run against the reference's run of the same seed, mean and interval over the seeds.
  RunDistances against_reference;
  // Every frame of the curves (front, covered area, volume, pile height) and the pile's profile at
  // the last snapshot: mean and interval over the seeds.
  std::vector<std::vector<Estimate>> curves;  // per metric; empty for the fields
  std::vector<Estimate> pile_profile_mm;
  std::vector<SettingTiming> timing;          // per backend of the study
};

// One metric along one knob's ladder.
struct LadderMetric {
  LadderFit fit;
  std::vector<Estimate> level_values;  // each level's value (the setting's value for the metric)
  Estimate extrapolated;               // Richardson's limit of the value, where asymptotic
  Estimate limit_distance;             // the finest level's distance from that limit, where asymptotic
};
struct LadderResult {
  std::string knob;
  std::vector<double> values;        // the levels that ran, coarse to fine
  std::vector<std::string> roles;    // "ladder", "reference", "refinement"
  std::vector<std::pair<double, std::string>> refused;  // levels that did not run, and why
  std::vector<LadderMetric> per_metric;  // in metrics()' order; empty fit where the metric is absent
};

// The reference's check along one knob: its distance to the next refinement against the seed
// spread, metric by metric.
struct KnobCheck {
  std::string knob;
  double refinement = kNaN;
  bool passed = false;
  std::string status;              // "below the seed spread", "undecided: ...", "refine: ...", "exact ...",
                                   // "not checked: ..."
  std::vector<Distance> distance;  // per metric (in metrics()' order)
};
struct ReferenceCheck {
  bool accepted = false;
  std::string verdict;             // what the study prints and writes
  std::vector<KnobCheck> knobs;
};

struct StudyResult {
  std::vector<SettingResult> settings;  // in the study's order
  std::vector<Estimate> seed_spread;    // per metric: the seed-to-seed spread at the reference
  RunDistances noise_floor;             // two reference runs of different seeds, over the pairs
  std::vector<bool> judged;             // per metric: moved by the seeds, so judged by the reference check
  std::vector<LadderResult> ladders;
  ReferenceCheck check;
};

// Throws std::runtime_error when the records do not fit the study (another study's, out of
// order, missing), when two backends' runs of one job disagree, or when the reference did not run.
StudyResult analyse(const Study& study, const std::vector<std::vector<std::uint8_t>>& records_in_job_order);

}  // namespace bleedsim
