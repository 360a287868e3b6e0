#include "core/study/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/effects/blend/blend_stage.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/io/scenario.h"
#include "core/runtime/hash.h"
#include "core/runtime/input_error.h"
#include "core/runtime/message_text.h"
#include "core/simulation/scene_check.h"
#include "core/simulation/simulation.h"
#include "core/study/job_record.h"
#include "core/study/study_metrics.h"

namespace bleedsim {
namespace {

using Clock = std::chrono::steady_clock;

// A knob's values keep its parameter's range (the table's, core/runtime/params.h); a factor's need
// only be positive. Each is given once: a repeat is a slip in the list, not a level.
void check_values(const Knob& knob, const std::vector<double>& values) {
  const std::string key = std::string("--knob ") + knob.name;
  if (values.empty()) throw InputError({}, key, "needs at least one value");
  for (auto v = values.begin(); v != values.end(); ++v)
    if (std::find(values.begin(), v, *v) != v)
      throw InputError({}, key, format_number(*v) + " is given twice: give each level once");
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

// Coarse to fine (the step size falling); check_values has made sure there are no repeats.
std::vector<double> coarse_to_fine(const Knob& knob, std::vector<double> values) {
  std::sort(values.begin(), values.end(),
            [&](double a, double b) { return knob_step(knob, a) > knob_step(knob, b); });
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

void check_seeds(int seeds) {
  if (seeds < 2)
    throw InputError({}, "--seeds", "needs at least 2 (got " + std::to_string(seeds) +
                                        "): a confidence interval needs two runs");
}

void set_duration(Scene& scene, double duration_s) {
  scene.duration_s = duration_s;
  if (scene.frame_count() < 1)
    throw InputError({}, "--duration-s",
                     format_number(duration_s) + " s is less than one frame at " +
                         format_number(scene.frame_rate_hz) + " Hz");
}

// Every knob the scene has, at its default levels; the time step's are chosen once the others' are
// known (choose_substep_levels).
std::vector<KnobLevels> default_knobs(const Scene& scene) {
  std::vector<KnobLevels> levels;
  for (const Knob& knob : knobs())
    if (knob.applies(scene))
      levels.push_back(
          {&knob, std::string(knob.name) == "substeps" ? std::vector<double>{} : knob.default_ladder(scene)});
  return levels;
}

// The knobs named (none: default_knobs), in the table's order (their addresses in it), each with its
// levels coarse to fine.
std::vector<StudyLadder> knob_ladders(const Scene& scene, std::vector<KnobLevels> knobs) {
  const bool defaults = knobs.empty();
  if (defaults) knobs = default_knobs(scene);
  std::stable_sort(knobs.begin(), knobs.end(),
                   [](const KnobLevels& a, const KnobLevels& b) { return a.knob < b.knob; });
  std::vector<StudyLadder> ladders;
  for (std::size_t i = 0; i < knobs.size(); ++i) {
    const KnobLevels& k = knobs[i];
    const std::string key = std::string("--knob ") + k.knob->name;
    if (i > 0 && knobs[i - 1].knob == k.knob) throw InputError({}, key, "is given twice: give its levels once");
    if (!k.knob->applies(scene))
      throw InputError({}, key, "this scene has nothing it changes (" + std::string(k.knob->trades) + ")");
    if (!k.levels.empty() || !defaults) check_values(*k.knob, k.levels);
    ladders.push_back({k.knob, coarse_to_fine(*k.knob, k.levels), {}, false, ""});
  }
  return ladders;
}

// `scene` with every knob of `ladders` at its finest but `knob` at `value` (none: all).
Scene at_reference_but(Scene scene, const std::vector<StudyLadder>& ladders, const Knob* knob, double value) {
  for (const StudyLadder& ladder : ladders) {
    if (ladder.values.empty()) continue;  // a default not yet chosen: the scene's own
    ladder.knob->apply(scene, ladder.knob == knob ? value : reference_value(ladder));
  }
  return scene;
}

// The fewest sub-steps that the stiffest contact of the study allows: the reference's, or a
// refinement's along a knob that stiffens it.
int fewest_substeps(const Scene& base, const std::vector<StudyLadder>& ladders) {
  int fewest = fewest_stable_substeps(at_reference_but(base, ladders, nullptr, 0));
  for (const StudyLadder& other : ladders)
    if (!other.values.empty())
      if (const std::optional<double> finer = refined_value(*other.knob, other.values))
        fewest = std::max(fewest, fewest_stable_substeps(at_reference_but(base, ladders, other.knob, *finer)));
  return fewest;
}

// The time step's default levels, where default_knobs left them: the fewest sub-steps the study
// allows, and twice that.
void choose_substep_levels(const Scene& base, std::vector<StudyLadder>& ladders) {
  for (StudyLadder& ladder : ladders) {
    if (!ladder.values.empty()) continue;
    Scene at_fewest = base;
    at_fewest.effects.get<ParticleParams>().substeps = fewest_substeps(base, ladders);
    ladder.values = coarse_to_fine(*ladder.knob, ladder.knob->default_ladder(at_fewest));
  }
}

// A ladder's settings: its coarser levels, the reference (setting 0) and its refinement, where the
// knob has one finer; or why it has none.
void add_ladder_settings(StudyLadder& ladder, std::vector<StudySetting>& settings) {
  const std::vector<double> levels = ladder.values;
  for (std::size_t i = 0; i + 1 < levels.size(); ++i) {
    ladder.settings.push_back(settings.size());
    settings.push_back({ladder.knob->name, levels[i], "ladder"});
  }
  ladder.settings.push_back(0);
  const double finest = levels.back();
  if (finest == ladder.knob->exact) {
    ladder.not_refined = "exact at " + format_number(finest) + ": nothing to refine";
  } else if (const std::optional<double> finer = refined_value(*ladder.knob, levels)) {
    ladder.values.push_back(*finer);
    ladder.settings.push_back(settings.size());
    ladder.refined = true;
    settings.push_back({ladder.knob->name, *finer, "refinement"});
  } else {
    ladder.not_refined = "no value finer than " + format_number(finest) + " within the knob's range";
  }
}

// The settings: the reference, the scene as it is, then each knob's coarser levels and its
// refinement.
std::vector<StudySetting> study_settings(std::vector<StudyLadder>& ladders) {
  std::vector<StudySetting> settings = {{"reference", 0, "reference"}, {"scene", 0, "scene"}};
  for (StudyLadder& ladder : ladders) add_ladder_settings(ladder, settings);
  return settings;
}

// Every setting is compared with the reference, so a study whose reference cannot run has nothing
// to measure.
void check_reference_runs(const Study& study) {
  const Scene reference = study.scene_for(0, 0);
  if (const ParamProblem problem = scene_problem(reference))
    throw InputError({}, "reference",
                     "the finest settings (" + study.reference_description() + ") cannot run: " + problem.text() +
                         "; narrow the knobs' ranges");
}

// The common grid: the coarsest panel any setting draws.
void choose_grid(const Scene& base, const std::vector<StudyLadder>& ladders, const std::vector<StudySetting>& settings,
                 int& grid_w, int& grid_h) {
  const StudyLadder* resolution = nullptr;
  for (const StudyLadder& ladder : ladders)
    if (std::string(ladder.knob->name) == "resolution") resolution = &ladder;
  const double finest_resolution = resolution ? reference_value(*resolution) : 1.0;
  grid_w = base.domain.width_px;
  grid_h = base.domain.height_px;
  for (const StudySetting& setting : settings) {
    const double f = setting.knob == "resolution" ? setting.value : setting.role == "scene" ? 1.0 : finest_resolution;
    grid_w = std::min(grid_w, resolution_pixels(base.domain.width_px, f));
    grid_h = std::min(grid_h, resolution_pixels(base.domain.height_px, f));
  }
  common_grid(grid_w, grid_h);
}

// Each setting's job cost (Study::job_cost).
std::vector<double> setting_costs(const Study& study) {
  std::vector<double> costs;
  for (std::size_t i = 0; i < study.settings().size(); ++i) {
    const Scene s = study.scene_for(i, 0);
    double per_frame = double(s.domain.width_px) * s.domain.height_px;
    if (s.effects.has<ParticleParams>())
      per_frame += double(resolve_particles(s).mechanics.substeps) * s.effects.get<ParticleParams>().capacity;
    costs.push_back(per_frame * study.frames_per_run());
  }
  return costs;
}

// Up to kSnapshots of a run's frames, spaced evenly, the last among them.
std::vector<int> snapshots_of(int frames) {
  const int snapshots = std::min(kSnapshots, frames);
  std::vector<int> chosen;
  for (int i = 0; i < snapshots; ++i) chosen.push_back(int((long(i) + 1) * frames / snapshots) - 1);
  return chosen;
}

// Study::key(): what the study runs, hashed, so that a record another study made is refused.
std::uint64_t study_key(const Study& study) {
  const Scene& base = study.scene();
  std::string identity = base.name + "|" + format_number(base.duration_s) + "|" + format_number(base.frame_rate_hz) +
                         "|" + std::to_string(base.domain.width_px) + "x" + std::to_string(base.domain.height_px) +
                         "|" + std::to_string(base.seed) + "|" + std::to_string(study.seeds()) + "|" +
                         std::to_string(study.grid_width()) + "x" + std::to_string(study.grid_height());
  for (const StudySetting& s : study.settings())
    identity += "|" + s.knob + " " + format_significant(s.value, 17) + " " + s.role;
  for (const BackendKind b : study.backends()) identity += std::string("|") + to_string(b);
  for (const Cut& c : base.cuts)
    for (const double v : {c.x_mm, c.y_mm, c.start_s, c.flow_mm3_per_s_per_mm, c.bleed_s})
      identity += " " + format_significant(v, 17);
  return fnv1a64(base.tissue.rgba.data(), base.tissue.rgba.size(), fnv1a64(identity.data(), identity.size()));
}

}  // namespace

double reference_value(const StudyLadder& ladder) { return ladder.values[ladder.values.size() - 1 - ladder.refined]; }

Study::Study(const Scene& scene, const StudySpec& spec) : base_(scene), spec_(spec) {
  check_seeds(spec_.seeds);
  if (spec_.backends.empty()) spec_.backends = {BackendKind::cpu};
  if (spec_.duration_s) set_duration(base_, *spec_.duration_s);
  pin_particle_model(base_);
  ladders_ = knob_ladders(base_, spec_.knobs);
  choose_substep_levels(base_, ladders_);
  settings_ = study_settings(ladders_);
  check_reference_runs(*this);
  choose_grid(base_, ladders_, settings_, grid_w_, grid_h_);
  setting_costs_ = setting_costs(*this);
  snapshots_ = snapshots_of(frames_per_run());
  key_ = study_key(*this);
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
  return bleedsim::at_reference_but(base_, ladders_, knob, value);
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
  const double gravity_x = s.effects.has<ParticleParams>() ? s.effects.get<ParticleParams>().gravity_x_mm_s2 : 0.0;
  const double gravity_y = s.effects.has<ParticleParams>() ? s.effects.get<ParticleParams>().gravity_y_mm_s2 : 1.0;
  r.grid_width = grid_w_;
  r.grid_height = grid_h_;
  r.snapshot_frames.assign(snapshots_.begin(), snapshots_.end());
  // The metrics read what the blend lays over the tissue.
  const char* film = blend_film_field(s);
  const char* stain = blend_stain_field(s);
  const bool particles = s.effects.has<ParticleParams>();
  const ParticleLifetime lifetime = particles ? resolve_particles(s).model.lifetime : ParticleLifetime{0, 0};
  std::size_t snapshot = 0;
  for (int k = 0; k < frames; ++k) {
    FrameFields fields{s.domain.width_px, s.domain.height_px, s.domain.width_mm, s.domain.height_mm, {}, {}, {}, {}, {},
                       lifetime};
    // Compute per frame: the step and the copy to the host of what a renderer would read.
    const Clock::time_point start = Clock::now();
    sim->step();
    if (film) fields.film_mm = copy_as<float>(*sim, film);
    if (stain) fields.stain = copy_as<float>(*sim, stain);
    fields.rgba = sim->copy_field("frame");
    r.frame_seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    if (particles) {
      fields.velocity = copy_as<float>(*sim, "particles/velocity");
      fields.age = copy_as<std::uint32_t>(*sim, "particles/age");
    }
    const FrameMeasures m = measure_frame(fields, film_on_grid(fields, grid_w_, grid_h_), grid_w_, grid_h_, gravity_x, gravity_y);
    r.front_mm.push_back(m.front_mm);
    r.covered_area_mm2.push_back(m.covered_area_mm2);
    r.volume_mm3.push_back(m.volume_mm3);
    r.pile_height_mm.push_back(m.pile_height_mm);
    r.fastest_mm_s.push_back(m.fastest_mm_s);
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
