#include "core/study/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/effects/blend_stage.h"
#include "core/effects/particle_model.h"
#include "core/io/scenario.h"
#include "core/runtime/hash.h"
#include "core/runtime/input_error.h"
#include "core/runtime/message_text.h"
#include "core/runtime/simulation.h"
#include "core/study/job_record.h"
#include "core/study/study_metrics.h"

namespace bleedsim {
namespace {

using Clock = std::chrono::steady_clock;

// A knob's values keep its parameter's range (the table's, core/runtime/params.h); a factor's need
// only be positive.
void check_values(const Knob& knob, const std::vector<double>& values) {
  const std::string key = std::string("--knob ") + knob.name;
  if (values.empty()) throw InputError({}, key, "needs at least one value");
  for (const double v : values) {
    if (!knob.param) {
      if (!(v > 0) || !std::isfinite(v)) throw InputError({}, key, "values must be positive (got " + format_number(v) + ")");
      continue;
    }
    const ParamView& param = scenario_param(knob.param);
    if (const ParamProblem problem = range_problem(knob.param, param.type, param.range, v))
      throw InputError({}, key, "values of " + problem.key + " " + problem.message);
  }
}

// Coarse to fine (the step size falling), without repeats.
std::vector<double> coarse_to_fine(const Knob& knob, std::vector<double> values) {
  std::sort(values.begin(), values.end(),
            [&](double a, double b) { return knob_step(knob, a) > knob_step(knob, b); });
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

template <class T>
std::vector<T> copy_as(const Simulation& sim, const char* name) {
  const std::vector<std::uint8_t> bytes = sim.copy_field(name);
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& more) {
  to.insert(to.end(), more.begin(), more.end());
}

}  // namespace

double reference_value(const StudyLadder& ladder) { return ladder.values[ladder.values.size() - 1 - ladder.refined]; }

Study::Study(const Scene& scene, const StudySpec& spec) : base_(scene), spec_(spec) {
  if (spec_.seeds < 2)
    throw InputError({}, "--seeds", "needs at least 2 (got " + std::to_string(spec_.seeds) +
                                        "): a confidence interval needs two runs");
  if (spec_.backends.empty()) spec_.backends = {BackendKind::cpu};
  if (spec_.duration_s) {
    base_.duration_s = *spec_.duration_s;
    if (base_.frame_count() < 1)
      throw InputError({}, "--duration-s",
                       format_number(*spec_.duration_s) + " s is less than one frame at " +
                           format_number(base_.frame_rate_hz) + " Hz");
  }
  pin_particle_model(base_);

  // The knobs, in the table's order (their addresses in it), each with its levels coarse to fine.
  // Without knobs named: every knob the scene has, at its default levels; the time step's are
  // chosen once the others' are known (below).
  const bool defaults = spec_.knobs.empty();
  if (defaults)
    for (const Knob& knob : knobs())
      if (knob.applies(base_)) spec_.knobs.push_back({&knob, std::string(knob.name) == "substeps"
                                                                 ? std::vector<double>{}
                                                                 : knob.default_ladder(base_)});
  std::stable_sort(spec_.knobs.begin(), spec_.knobs.end(),
                   [](const KnobLevels& a, const KnobLevels& b) { return a.knob < b.knob; });
  for (std::size_t i = 0; i < spec_.knobs.size(); ++i) {
    const KnobLevels& k = spec_.knobs[i];
    const std::string key = std::string("--knob ") + k.knob->name;
    if (i > 0 && spec_.knobs[i - 1].knob == k.knob) throw InputError({}, key, "is given twice: give its levels once");
    if (!k.knob->applies(base_))
      throw InputError({}, key, "this scene has nothing it changes (" + std::string(k.knob->trades) + ")");
    if (!k.levels.empty() || !defaults) check_values(*k.knob, k.levels);
    ladders_.push_back({k.knob, coarse_to_fine(*k.knob, k.levels), {}, false, ""});
  }
  // The time step's default levels: the fewest sub-steps that the stiffest contact of the study
  // allows (the reference's, or a refinement's along a knob that stiffens it), and twice that.
  for (StudyLadder& ladder : ladders_) {
    if (!ladder.values.empty()) continue;
    int fewest = fewest_stable_substeps(at_reference_but(nullptr, 0));
    for (const StudyLadder& other : ladders_)
      if (!other.values.empty())
        if (const std::optional<double> finer = refined_value(*other.knob, other.values))
          fewest = std::max(fewest, fewest_stable_substeps(at_reference_but(other.knob, *finer)));
    Scene at_fewest = base_;
    at_fewest.particles->substeps = fewest;
    ladder.values = coarse_to_fine(*ladder.knob, ladder.knob->default_ladder(at_fewest));
  }

  // The settings: the reference, the scene as it is, then each knob's coarser levels and its
  // refinement.
  settings_.push_back({"reference", 0, "reference"});
  settings_.push_back({"scene", 0, "scene"});
  for (StudyLadder& ladder : ladders_) {
    const std::vector<double> levels = ladder.values;
    for (std::size_t i = 0; i + 1 < levels.size(); ++i) {
      ladder.settings.push_back(settings_.size());
      settings_.push_back({ladder.knob->name, levels[i], "ladder"});
    }
    ladder.settings.push_back(0);
    const double finest = levels.back();
    if (finest == ladder.knob->exact) {
      ladder.not_refined = "exact at " + format_number(finest) + ": nothing to refine";
    } else if (const std::optional<double> finer = refined_value(*ladder.knob, levels)) {
      ladder.values.push_back(*finer);
      ladder.settings.push_back(settings_.size());
      ladder.refined = true;
      settings_.push_back({ladder.knob->name, *finer, "refinement"});
    } else {
      ladder.not_refined = "no value finer than " + format_number(finest) + " within the knob's range";
    }
  }
  const Scene reference = scene_for(0, 0);
  if (const ParamProblem problem = scene_problem(reference))
    throw InputError({}, "reference",
                     "the finest settings (" + reference_description() + ") cannot run: " + problem.text() +
                         "; narrow the knobs' ranges");

  // The common grid: the coarsest panel any setting draws.
  const StudyLadder* resolution = nullptr;
  for (const StudyLadder& ladder : ladders_)
    if (std::string(ladder.knob->name) == "resolution") resolution = &ladder;
  const double finest_resolution = resolution ? reference_value(*resolution) : 1.0;
  grid_w_ = base_.domain.width_px;
  grid_h_ = base_.domain.height_px;
  for (const StudySetting& setting : settings_) {
    const double f = setting.knob == "resolution" ? setting.value : setting.role == "scene" ? 1.0 : finest_resolution;
    grid_w_ = std::min(grid_w_, resolution_pixels(base_.domain.width_px, f));
    grid_h_ = std::min(grid_h_, resolution_pixels(base_.domain.height_px, f));
  }
  common_grid(grid_w_, grid_h_);
  for (std::size_t i = 0; i < settings_.size(); ++i) {
    const Scene s = scene_for(i, 0);
    double per_frame = double(s.domain.width_px) * s.domain.height_px;
    if (s.particles)
      per_frame += double(particle_mechanics(*s.particles, s.domain, s.frame_rate_hz).substeps) * s.particles->capacity;
    setting_costs_.push_back(per_frame * frames_per_run());
  }
  const int frames = frames_per_run(), snapshots = std::min(kSnapshots, frames);
  for (int i = 0; i < snapshots; ++i) snapshots_.push_back(int((long(i) + 1) * frames / snapshots) - 1);

  std::string identity = base_.name + "|" + format_number(base_.duration_s) + "|" + format_number(base_.frame_rate_hz) +
                         "|" + std::to_string(base_.domain.width_px) + "x" + std::to_string(base_.domain.height_px) +
                         "|" + std::to_string(base_.seed) + "|" + std::to_string(spec_.seeds) + "|" +
                         std::to_string(grid_w_) + "x" + std::to_string(grid_h_);
  for (const StudySetting& s : settings_) identity += "|" + s.knob + " " + format_significant(s.value, 17) + " " + s.role;
  for (const BackendKind b : spec_.backends) identity += std::string("|") + to_string(b);
  for (const Cut& c : base_.cuts)
    for (const double v : {c.x_mm, c.y_mm, c.start_s, c.flow_mm3_per_s_per_mm, c.bleed_s})
      identity += " " + format_significant(v, 17);
  key_ = fnv1a64(base_.tissue.rgba.data(), base_.tissue.rgba.size(), fnv1a64(identity.data(), identity.size()));
}

std::uint64_t Study::seed_of(int seed_index) const {
  return (base_.seed + std::uint64_t(seed_index)) & ((std::uint64_t(1) << 63) - 1);
}

std::string Study::reference_description() const {
  std::string text;
  for (const StudyLadder& ladder : ladders_)
    text += (text.empty() ? "" : ", ") + std::string(ladder.knob->name) + " " +
            format_number(reference_value(ladder));
  return text;
}

Scene Study::at_reference_but(const Knob* knob, double value) const {
  Scene s = base_;
  for (const StudyLadder& ladder : ladders_) {
    if (ladder.values.empty()) continue;  // a default not yet chosen: the scene's own
    ladder.knob->apply(s, ladder.knob == knob ? value : reference_value(ladder));
  }
  return s;
}

Scene Study::scene_for(std::size_t setting, int seed_index) const {
  const StudySetting& st = settings_.at(setting);
  // The knobs draw the tissue at a new resolution from the scene's own seed: the ensemble's seed
  // is set after them.
  Scene s = st.role == "scene" ? base_ : at_reference_but(st.role == "reference" ? nullptr : find_knob(st.knob), st.value);
  s.seed = seed_of(seed_index);
  return s;
}

Study::Job Study::job(std::size_t j) const {
  if (j >= job_count())
    throw std::out_of_range("study job " + std::to_string(j) + ": the study has " + std::to_string(job_count()));
  const std::size_t per_setting = std::size_t(spec_.seeds) * spec_.backends.size();
  return {j / per_setting, int(j % per_setting / spec_.backends.size()), spec_.backends[j % spec_.backends.size()]};
}

double Study::job_cost(std::size_t j) const { return setting_costs_[job(j).setting]; }

std::vector<std::uint8_t> Study::run_job(std::size_t j, BackendKind backend, int cuda_device,
                                         const std::function<void()>& frame_done) const {
  const Job job = this->job(j);
  JobRecord r;
  r.study_key = key_;
  r.job = std::uint32_t(j);
  r.setting = std::uint32_t(job.setting);
  r.seed_index = std::uint32_t(job.seed_index);
  r.seed = seed_of(job.seed_index);
  r.backend = backend;
  const int frames = frames_per_run();
  const auto done = [&](int count) {
    if (frame_done)
      for (int k = 0; k < count; ++k) frame_done();
  };
  std::unique_ptr<Simulation> sim;
  try {
    const BackendChoice choice{backend == BackendKind::cuda ? BackendChoice::Want::cuda : BackendChoice::Want::cpu,
                               spec_.cpu_threads, cuda_device};
    sim = std::make_unique<Simulation>(scene_for(job.setting, job.seed_index), choice);
  } catch (const std::invalid_argument& e) {
    r.status = std::string("refused: ") + e.what();
  } catch (const InputError& e) {
    r.status = std::string("refused: ") + e.what();
  }
  if (!sim) {
    done(frames);
    return serialize(r);
  }
  r.device = sim->backend().device_name();
  const Scene& s = sim->scene();
  const double gravity_x = s.particles ? s.particles->gravity_x_mm_s2 : 0.0;
  const double gravity_y = s.particles ? s.particles->gravity_y_mm_s2 : 1.0;
  r.grid_width = grid_w_;
  r.grid_height = grid_h_;
  r.snapshot_frames.assign(snapshots_.begin(), snapshots_.end());
  // The metrics read what the blend lays over the tissue.
  const char* film = blend_film_field(s);
  const char* stain = blend_stain_field(s);
  std::size_t snapshot = 0;
  for (int k = 0; k < frames; ++k) {
    FrameFields fields{s.domain.width_px, s.domain.height_px, s.domain.width_mm, s.domain.height_mm, {}, {}, {}};
    // Compute per frame: the step and the copy to the host of what a renderer would read.
    const Clock::time_point start = Clock::now();
    sim->step();
    if (film) fields.film_mm = copy_as<float>(*sim, film);
    if (stain) fields.stain = copy_as<float>(*sim, stain);
    fields.rgba = sim->copy_field("frame");
    r.frame_seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    const FrameMeasures m = measure_frame(fields, film_on_grid(fields, grid_w_, grid_h_), grid_w_, grid_h_, gravity_x, gravity_y);
    r.front_mm.push_back(m.front_mm);
    r.covered_area_mm2.push_back(m.covered_area_mm2);
    r.volume_mm3.push_back(m.volume_mm3);
    r.pile_height_mm.push_back(m.pile_height_mm);
    if (snapshot < snapshots_.size() && snapshots_[snapshot] == k) {
      const GridFrame g = on_grid(fields, grid_w_, grid_h_);
      append(r.film_mm, g.film_mm);
      append(r.stain, g.stain);
      append(r.rgb, g.rgb);
      ++snapshot;
    }
    done(1);
  }
  return serialize(r);
}

std::vector<std::vector<std::uint8_t>> run_all_jobs(const Study& study, const std::function<void()>& frame_done) {
  std::vector<std::vector<std::uint8_t>> records;
  for (std::size_t j = 0; j < study.job_count(); ++j) records.push_back(study.run_job(j, study.job(j).backend, 0, frame_done));
  return records;
}

}  // namespace bleedsim
