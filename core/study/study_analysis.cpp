#include "core/study/study_analysis.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "core/runtime/hash.h"
#include "core/runtime/message_text.h"
#include "core/runtime/timing_summary.h"
#include "core/study/job_record.h"
#include "core/study/study_metrics.h"

namespace bleedsim {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The seeds move a metric when its spread is more than this fraction of its largest component
// (float32 sums round at 6e-8 of their size).
constexpr double kMovedBySeeds = 1e-6;

// A metric's components in one run; empty where the run has none of it. The grid's cells are
// cell_height_mm high, the frames frame_s apart.
std::vector<double> components(const JobRecord& r, Metric m, double cell_height_mm, double frame_s) {
  const auto curve = [](const std::vector<double>& v) {
    return v.empty() || std::isnan(v.front()) ? std::vector<double>{} : v;
  };
  switch (m) {
    case Metric::film: return std::vector<double>(r.film_mm.begin(), r.film_mm.end());
    case Metric::stain: return std::vector<double>(r.stain.begin(), r.stain.end());
    case Metric::front: return curve(r.front_mm);
    case Metric::covered_area: return curve(r.covered_area_mm2);
    case Metric::volume: return curve(r.volume_mm3);
    case Metric::rest:
      if (curve(r.fastest_mm_s).empty()) return {};
      return {rest_time_s(r.fastest_mm_s, frame_s)};
    case Metric::pile_height: {
      std::vector<double> profile;
      const std::size_t cells = std::size_t(r.grid_width) * std::size_t(r.grid_height);
      for (std::size_t s = 0; cells > 0 && s < r.film_mm.size() / cells; ++s) {
        const std::vector<float> film(r.film_mm.begin() + long(s * cells), r.film_mm.begin() + long((s + 1) * cells));
        const std::vector<double> heights = pile_heights_mm(film, r.grid_width, r.grid_height, cell_height_mm);
        profile.insert(profile.end(), heights.begin(), heights.end());
      }
      return profile;
    }
  }
  return {};
}

const std::vector<double>* per_frame(const JobRecord& r, Metric m) {
  switch (m) {
    case Metric::front: return &r.front_mm;
    case Metric::covered_area: return &r.covered_area_mm2;
    case Metric::volume: return &r.volume_mm3;
    case Metric::pile_height: return &r.pile_height_mm;
    default: return nullptr;
  }
}

double mean_of(const std::vector<double>& v) {
  double sum = 0;
  for (const double x : v) sum += x;
  return sum / double(v.size());
}

double psnr_or_infinity(double mse) { return mse <= 0 ? kInfinity : psnr_db(mse); }

GridFrame grid_of(const JobRecord& r) { return {r.film_mm, r.stain, r.rgb}; }

std::string number(double v) { return format_significant(v, 3); }

// The records, checked against the study and one another, by setting and seed.
class Runs {
 public:
  Runs(const Study& study, const std::vector<std::vector<std::uint8_t>>& bytes) : study_(study) {
    if (bytes.size() != study.job_count())
      throw std::runtime_error("study analysis: the study has " + std::to_string(study.job_count()) + " jobs, and " +
                               std::to_string(bytes.size()) + " records were given");
    records_.reserve(bytes.size());
    for (std::size_t j = 0; j < bytes.size(); ++j) {
      try {
        records_.push_back(deserialize(bytes[j]));
      } catch (const std::runtime_error& e) {
        throw std::runtime_error("study analysis: record " + std::to_string(j) + ": " + e.what());
      }
      const JobRecord& r = records_.back();
      const Study::Job job = study.job(j);
      if (r.study_key != study.key())
        throw std::runtime_error("study analysis: record " + std::to_string(j) + " was made by another study (key " +
                                 hex64(r.study_key) + ", this one's " + hex64(study.key()) +
                                 "): the same scene, knobs, seeds and duration make the same study");
      if (r.job != j || r.setting != job.setting || int(r.seed_index) != job.seed_index)
        throw std::runtime_error("study analysis: record " + std::to_string(j) + " is job " + std::to_string(r.job) +
                                 ": the records must come in job order");
    }
    // The first backend's record of each (setting, seed); the others' data must be the same bytes.
    const std::size_t backends = study.backends().size();
    for (std::size_t j = 0; j < records_.size(); j += backends)
      for (std::size_t b = 1; b < backends; ++b)
        if (data_bytes(records_[j + b]) != data_bytes(records_[j]))
          throw std::runtime_error("study analysis: job " + std::to_string(j + b) + " (" +
                                   describe(study.job(j).setting) + ", seed " + std::to_string(records_[j].seed) +
                                   ") gives other data on " + to_string(records_[j + b].backend) + " than on " +
                                   to_string(records_[j].backend) + ": the backends must give the same bytes");
  }

  const JobRecord& run(std::size_t setting, int seed) const {
    return records_[(setting * std::size_t(study_.seeds()) + std::size_t(seed)) * study_.backends().size()];
  }
  const JobRecord& run_on(std::size_t setting, int seed, std::size_t backend) const {
    return records_[(setting * std::size_t(study_.seeds()) + std::size_t(seed)) * study_.backends().size() + backend];
  }
  std::string status(std::size_t setting) const {
    for (int s = 0; s < study_.seeds(); ++s)
      if (run(setting, s).status != "ok") return run(setting, s).status;
    return "ok";
  }
  // The metric's components per seed; empty where the setting's runs have none.
  SeedValues values(std::size_t setting, Metric m) const {
    SeedValues v;
    const double cell_height = study_.scene().domain.height_mm / study_.grid_height();
    const double frame_s = 1.0 / study_.scene().frame_rate_hz;
    for (int s = 0; s < study_.seeds(); ++s) {
      v.push_back(components(run(setting, s), m, cell_height, frame_s));
      if (v.back().empty()) return {};
    }
    return v;
  }
  std::string describe(std::size_t setting) const {
    const StudySetting& st = study_.settings()[setting];
    return st.role == "reference" || st.role == "scene" ? st.role : st.knob + " " + format_number(st.value);
  }

 private:
  const Study& study_;
  std::vector<JobRecord> records_;
};

RunDistances estimates(const std::vector<RunDistance>& per_seed) {
  std::vector<double> l1, l2, mse, stain;
  for (const RunDistance& d : per_seed) {
    l1.push_back(d.film_l1_mm);
    l2.push_back(d.film_l2_mm);
    mse.push_back(d.frame_mse);
    stain.push_back(d.stain_l1);
  }
  RunDistances out{mean_ci(l1), mean_ci(l2), mean_ci(mse), {}, mean_ci(stain)};
  out.frame_psnr_db = {psnr_or_infinity(out.frame_mse.value), psnr_or_infinity(out.frame_mse.hi),
                       psnr_or_infinity(out.frame_mse.lo)};
  return out;
}

std::vector<Estimate> per_component_ci(const std::vector<const std::vector<double>*>& seeds) {
  std::vector<Estimate> out;
  for (std::size_t c = 0; c < seeds.front()->size(); ++c) {
    std::vector<double> values;
    for (const std::vector<double>* s : seeds) values.push_back((*s)[c]);
    out.push_back(mean_ci(values));
  }
  return out;
}

std::vector<SettingTiming> timings(const Study& study, const Runs& runs, std::size_t setting) {
  std::vector<SettingTiming> out;
  for (std::size_t b = 0; b < study.backends().size(); ++b) {
    SettingTiming t;
    t.backend = study.backends()[b];
    std::vector<double> all;
    for (int s = 0; s < study.seeds(); ++s) {
      const JobRecord& r = runs.run_on(setting, s, b);
      if (r.frame_seconds.empty()) continue;
      t.device = r.device;
      t.frame_seconds.push_back(r.frame_seconds);
      all.insert(all.end(), r.frame_seconds.begin(), r.frame_seconds.end());
      const double p50 = 1e3 * percentiles_of(r.frame_seconds).p50;
      t.ms_p50_low = std::isnan(t.ms_p50_low) ? p50 : std::min(t.ms_p50_low, p50);
      t.ms_p50_high = std::isnan(t.ms_p50_high) ? p50 : std::max(t.ms_p50_high, p50);
    }
    if (!all.empty()) {
      const Percentiles p = percentiles_of(all);
      t.ms_p50 = 1e3 * p.p50;
      t.ms_p99 = 1e3 * p.p99;
    }
    out.push_back(t);
  }
  return out;
}

SettingResult setting_result(const Study& study, const Runs& runs, std::size_t i,
                             const std::vector<SeedValues>& reference) {
  SettingResult out;
  out.setting = study.settings()[i];
  out.status = runs.status(i);
  out.timing = timings(study, runs, i);
  const std::size_t m_count = metrics().size();
  out.value.assign(m_count, {});
  out.distance.assign(m_count, {});
  out.per_seed.assign(m_count, {});
  out.curves.assign(m_count, {});
  if (out.status != "ok") return out;
  for (std::size_t m = 0; m < m_count; ++m) {
    const SeedValues x = runs.values(i, metrics()[m].metric);
    if (x.empty() || reference[m].empty()) continue;
    for (const std::vector<double>& seed : x) out.per_seed[m].push_back(mean_of(seed));
    out.value[m] = mean_ci(out.per_seed[m]);
    out.distance[m] = ensemble_distance(x, reference[m]);
    std::vector<const std::vector<double>*> frames;
    for (int s = 0; s < study.seeds(); ++s)
      if (const std::vector<double>* curve = per_frame(runs.run(i, s), metrics()[m].metric)) frames.push_back(curve);
    if (!frames.empty()) out.curves[m] = per_component_ci(frames);
  }
  std::vector<RunDistance> against;
  for (int s = 0; s < study.seeds(); ++s) against.push_back(run_distance(grid_of(runs.run(i, s)), grid_of(runs.run(0, s))));
  out.against_reference = estimates(against);
  // The pile's profile at the last snapshot: the last grid-width components of the pile metric.
  const SeedValues pile = runs.values(i, Metric::pile_height);
  if (!pile.empty()) {
    const std::size_t w = std::size_t(study.grid_width()), last = pile.front().size() - w;
    std::vector<std::vector<double>> profiles;
    std::vector<const std::vector<double>*> seeds;
    for (const std::vector<double>& seed : pile) profiles.emplace_back(seed.begin() + long(last), seed.end());
    for (const std::vector<double>& p : profiles) seeds.push_back(&p);
    out.pile_profile_mm = per_component_ci(seeds);
  }
  return out;
}

LadderResult ladder_result(const Study& study, const Runs& runs, const StudyLadder& ladder,
                           const std::vector<SettingResult>& settings) {
  LadderResult out;
  out.knob = ladder.knob->name;
  std::vector<std::size_t> ran;
  for (std::size_t l = 0; l < ladder.settings.size(); ++l) {
    const std::size_t i = ladder.settings[l];
    if (settings[i].status != "ok") {
      out.refused.emplace_back(ladder.values[l], settings[i].status);
      continue;
    }
    ran.push_back(l);
    out.values.push_back(ladder.values[l]);
    out.roles.push_back(study.settings()[i].role);
  }
  out.per_metric.assign(metrics().size(), {});
  if (ran.size() < 2) return out;
  for (std::size_t m = 0; m < metrics().size(); ++m) {
    std::vector<SeedValues> levels;
    for (const std::size_t l : ran) levels.push_back(runs.values(ladder.settings[l], metrics()[m].metric));
    if (levels.front().empty()) continue;
    LadderInput in;
    for (std::size_t k = 0; k < ran.size(); ++k) {
      in.step.push_back(knob_step(*ladder.knob, out.values[k]));
      in.labels.push_back(format_number(out.values[k]));
      in.levels.push_back(&levels[k]);
    }
    LadderMetric& lm = out.per_metric[m];
    lm.fit = fit_ladder(in);
    for (const std::size_t l : ran) lm.level_values.push_back(settings[ladder.settings[l]].value[m]);
    if (lm.fit.asymptotic_from < 0) continue;
    // Richardson from the two finest levels, seed by seed, at the finest order estimate.
    const std::size_t f = ran.size() - 1;
    const double w = richardson_weight(in.step[f - 1], in.step[f], lm.fit.order);
    std::vector<double> limits;
    for (int s = 0; s < study.seeds(); ++s) {
      const double fine = mean_of(levels[f][std::size_t(s)]), coarse = mean_of(levels[f - 1][std::size_t(s)]);
      limits.push_back(fine - (coarse - fine) * w);
    }
    lm.extrapolated = mean_ci(limits);
    const Estimate& last = lm.fit.differences.back().rms;
    lm.limit_distance = {last.value * w, last.lo * w, last.hi * w};
  }
  return out;
}

std::string distance_text(const MetricInfo& info, const Distance& d, const Estimate& spread) {
  return std::string(info.name) + " by " + number(d.rms.value) + " [" + number(d.rms.lo) + ", " + number(d.rms.hi) +
         "] " + info.unit + " against a seed spread of " + number(spread.value);
}

// Along each knob: the reference's next refinement moves each judged metric's ensemble mean by a
// distance D [lo, hi]; the knob is to be refined where D is above the seed spread beyond its
// interval (lo > spread), undecided where the interval reaches past the spread, and passes
// otherwise. The reference is accepted when no knob is to be refined and every knob was checked.
ReferenceCheck check_reference(const Study& study, const StudyResult& result) {
  ReferenceCheck check;
  check.accepted = true;
  std::string refine, unchecked, undecided;
  for (const StudyLadder& ladder : study.ladders()) {
    KnobCheck k;
    k.knob = ladder.knob->name;
    if (!ladder.refined) {
      k.passed = ladder.not_refined.rfind("exact", 0) == 0;
      k.status = k.passed ? ladder.not_refined : "not checked: " + ladder.not_refined;
      if (!k.passed) unchecked += (unchecked.empty() ? "" : "; ") + k.knob + " (" + ladder.not_refined + ")";
    } else {
      const SettingResult& finer = result.settings[ladder.settings.back()];
      k.refinement = ladder.values.back();
      k.distance = finer.distance;
      if (finer.status != "ok") {
        k.status = "not checked: its refinement to " + format_number(k.refinement) + " did not run (" + finer.status + ")";
        unchecked += (unchecked.empty() ? "" : "; ") + k.knob + " (" + k.status.substr(13) + ")";
      } else {
        k.passed = true;
        std::string above, straddles;
        for (std::size_t m = 0; m < metrics().size(); ++m) {
          if (!result.judged[m]) continue;
          const Distance& d = finer.distance[m];
          const double spread = result.seed_spread[m].value;
          // Without an interval (two seeds) the estimate itself decides.
          const double low = std::isnan(d.rms.lo) ? d.rms.value : d.rms.lo;
          const double high = std::isnan(d.rms.hi) ? d.rms.value : d.rms.hi;
          const std::string text = distance_text(metrics()[m], d, result.seed_spread[m]);
          if (low > spread) above += (above.empty() ? "" : "; ") + text;
          else if (high >= spread) straddles += (straddles.empty() ? "" : "; ") + text;
        }
        k.passed = above.empty();
        const std::string to = "its refinement to " + format_number(k.refinement) + " moves ";
        if (!k.passed) {
          k.status = "refine: " + to + above;
          refine += (refine.empty() ? "" : "; ") + k.knob + " (" + to + above + ")";
        } else if (!straddles.empty()) {
          k.status = "undecided: " + to + straddles + " (the interval reaches past the spread: more seeds would tell)";
          undecided += (undecided.empty() ? "" : "; ") + k.knob + " (" + to + straddles + ")";
        } else {
          k.status = "below the seed spread";
        }
      }
    }
    check.accepted = check.accepted && k.passed;
    check.knobs.push_back(k);
  }
  std::string judged;
  for (std::size_t m = 0; m < metrics().size(); ++m)
    if (result.judged[m]) judged += std::string(judged.empty() ? "" : ", ") + metrics()[m].name;
  if (check.accepted) {
    check.verdict = "accepted: along every knob the reference's next refinement moves no judged metric (" + judged +
                    ") by more than the seed spread beyond its 95 % interval";
    if (!undecided.empty()) check.verdict += "; undecided (the interval reaches past the spread): " + undecided;
  } else {
    check.verdict = "not accepted:";
    if (!refine.empty()) check.verdict += " refine " + refine + ".";
    if (!unchecked.empty()) check.verdict += " Not checked: " + unchecked + ".";
    if (!undecided.empty()) check.verdict += " Undecided: " + undecided + ".";
  }
  return check;
}

}  // namespace

const std::vector<MetricInfo>& metrics() {
  static const std::vector<MetricInfo> table = {
      {Metric::film, "film_mm", "mm", "the film's thickness on the grid's cells at the snapshot frames"},
      {Metric::stain, "stain", "1", "the spread's stain on the grid's cells at the snapshot frames"},
      {Metric::front, "front_mm", "mm", "how far the blood has run along gravity, every frame"},
      {Metric::covered_area, "covered_area_mm2", "mm²", "the area under film thicker than 0.01 mm, every frame"},
      {Metric::volume, "volume_mm3", "mm³", "the film's volume in view, every frame"},
      {Metric::pile_height, "pile_height_mm", "mm", "the pile's height in each column of the grid at the snapshot frames"},
      {Metric::rest, "rest_s", "s", "when the blood came to rest for good: the end of the last frame in which a particle moved faster than 0.1 mm/s"},
  };
  return table;
}

StudyResult analyse(const Study& study, const std::vector<std::vector<std::uint8_t>>& records) {
  const Runs runs(study, records);
  if (runs.status(0) != "ok")
    throw std::runtime_error("study analysis: the reference did not run: " + runs.status(0));
  StudyResult result;
  std::vector<SeedValues> reference;
  for (const MetricInfo& info : metrics()) {
    reference.push_back(runs.values(0, info.metric));
    result.seed_spread.push_back(reference.back().empty() ? Estimate{} : seed_spread(reference.back()));
    // A metric the seeds move is judged by the reference check; one they do not (the spread's stain,
    // which has no randomness; the volume in view where no blood leaves it) has no noise floor to
    // be judged against: its spread is float rounding, under a millionth of its value.
    double scale = 0;
    for (const std::vector<double>& seed : reference.back())
      for (const double v : seed) scale = std::max(scale, std::abs(v));
    result.judged.push_back(result.seed_spread.back().value > kMovedBySeeds * scale);
  }
  for (std::size_t i = 0; i < study.settings().size(); ++i)
    result.settings.push_back(setting_result(study, runs, i, reference));
  // Two reference runs of different seeds: the single-run distances' floor.
  const std::size_t n = std::size_t(study.seeds());
  std::vector<RunDistance> pairs(n * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) pairs[a * n + b] = run_distance(grid_of(runs.run(0, int(a))), grid_of(runs.run(0, int(b))));
  const auto floor_of = [&](double RunDistance::*member) {
    return pair_mean(n, [&](std::size_t a, std::size_t b) { return pairs[a * n + b].*member; });
  };
  result.noise_floor = {floor_of(&RunDistance::film_l1_mm), floor_of(&RunDistance::film_l2_mm),
                        floor_of(&RunDistance::frame_mse), {}, floor_of(&RunDistance::stain_l1)};
  const Estimate& mse = result.noise_floor.frame_mse;
  result.noise_floor.frame_psnr_db = {psnr_or_infinity(mse.value), psnr_or_infinity(mse.hi), psnr_or_infinity(mse.lo)};
  for (const StudyLadder& ladder : study.ladders()) result.ladders.push_back(ladder_result(study, runs, ladder, result.settings));
  result.check = check_reference(study, result);
  return result;
}

}  // namespace bleedsim
