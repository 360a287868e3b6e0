#include "core/study/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include "core/effects/blend_stage.h"
#include "core/io/scenario.h"
#include "core/runtime/input_error.h"
#include "core/runtime/message_text.h"
#include "core/runtime/simulation.h"

namespace bleedsim {
namespace {

using Clock = std::chrono::steady_clock;

SourcePlace no_place() { return {}; }

// The finer end of a knob's values (its base included).
double finest(const Knob& knob, const std::vector<double>& values, double base) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return knob.finer_is_larger ? std::max(*high, base) : std::min(*low, base);
}

// A knob's values keep its parameter's range (the table's, core/runtime/params.h); a factor's need
// only be positive.
void check_values(const Knob& knob, const std::vector<double>& values) {
  const std::string key = std::string("--knob ") + knob.name;
  if (values.empty()) throw InputError(no_place(), key, "needs at least one value");
  for (const double v : values) {
    if (!knob.param) {
      if (!(v > 0) || !std::isfinite(v)) throw InputError(no_place(), key, "values must be positive (got " + format_number(v) + ")");
      continue;
    }
    const ParamView& param = scenario_param(knob.param);
    if (const ParamProblem problem = range_problem(knob.param, param.type, param.range, v))
      throw InputError(no_place(), key, "values of " + problem.key + " " + problem.message);
  }
}

template <class T>
std::vector<T> copy_as(const Simulation& sim, const char* name) {
  const std::vector<std::uint8_t> bytes = sim.copy_field(name);
  std::vector<T> values(bytes.size() / sizeof(T));
  std::copy(bytes.begin(), bytes.end(), reinterpret_cast<std::uint8_t*>(values.data()));
  return values;
}

}  // namespace

Study::Study(const Scene& scene, const StudySpec& spec) : base_(scene), spec_(spec) {
  if (spec_.duration_s) {
    base_.duration_s = *spec_.duration_s;
    if (base_.frame_count() < 1)
      throw InputError(no_place(), "--duration-s",
                       format_number(*spec_.duration_s) + " s is less than one frame at " +
                           format_number(base_.frame_rate_hz) + " Hz");
  }
  if (spec_.sweeps.empty())
    for (const Knob& knob : knobs())
      if (knob.applies(base_)) spec_.sweeps.push_back({&knob, knob.default_sweep(base_)});
  for (KnobSweep& sweep : spec_.sweeps) {
    if (!sweep.knob->applies(base_))
      throw InputError(no_place(), std::string("--knob ") + sweep.knob->name,
                       "this scene has nothing it changes (" + std::string(sweep.knob->trades) + ")");
    check_values(*sweep.knob, sweep.values);
    std::sort(sweep.values.begin(), sweep.values.end());
    sweep.values.erase(std::unique(sweep.values.begin(), sweep.values.end()), sweep.values.end());
  }
  // The knobs in the table's order (their addresses in it), as the reference applies them.
  std::stable_sort(spec_.sweeps.begin(), spec_.sweeps.end(),
                   [](const KnobSweep& a, const KnobSweep& b) { return a.knob < b.knob; });

  settings_.push_back({"reference", 0, "reference"});
  settings_.push_back({"reference_check", 0, "reference_check"});
  for (const KnobSweep& sweep : spec_.sweeps) {
    const double base = sweep.knob->base(base_);
    std::vector<double> values = sweep.values;
    if (std::find(values.begin(), values.end(), base) == values.end()) values.push_back(base);
    std::sort(values.begin(), values.end());
    for (const double v : values) settings_.push_back({sweep.knob->name, v, v == base ? "base" : "sweep"});
  }
  // The common grid: the coarsest panel any setting draws.
  grid_w_ = base_.domain.width_px;
  grid_h_ = base_.domain.height_px;
  for (const StudySetting& setting : settings_) {
    if (setting.knob != "resolution") continue;
    Scene s = base_;
    s.domain.width_px = std::max(1, int(std::round(s.domain.width_px * setting.value)));
    s.domain.height_px = std::max(1, int(std::round(s.domain.height_px * setting.value)));
    grid_w_ = std::min(grid_w_, s.domain.width_px);
    grid_h_ = std::min(grid_h_, s.domain.height_px);
  }
  common_grid(grid_w_, grid_h_);
}

long Study::frames_per_run() const { return long(base_.frame_count()); }

std::string Study::reference_description() const {
  std::string text;
  for (const KnobSweep& sweep : spec_.sweeps)
    text += (text.empty() ? "" : ", ") + std::string(sweep.knob->name) + " " +
            format_number(finest(*sweep.knob, sweep.values, sweep.knob->base(base_)));
  return text;
}

// The base scene with one knob set, or with every knob at its finest (the reference), or that with
// its time step halved (or, without particles, its pixels doubled): the reference's check.
Scene Study::with(const StudySetting& setting) const {
  Scene s = base_;
  const bool reference = setting.role == "reference" || setting.role == "reference_check";
  for (const KnobSweep& sweep : spec_.sweeps) {
    const Knob& knob = *sweep.knob;
    if (reference) knob.apply(s, finest(knob, sweep.values, knob.base(base_)));
    else if (setting.knob == knob.name) knob.apply(s, setting.value);
  }
  // Both knobs refine what the scene has as it is now: more sub-steps never soften the contact.
  if (setting.role == "reference_check") {
    if (s.particles) find_knob("substeps")->apply(s, 2.0 * s.particles->substeps);
    else find_knob("resolution")->apply(s, 2.0);
  }
  return s;
}

StudyRun Study::run_one(const StudySetting& setting, BackendKind backend, const std::vector<GridFrame>& reference,
                        const std::vector<GridFrame>* knob_reference, std::vector<GridFrame>* keep,
                        const std::function<void()>& frame_done) const {
  StudyRun run;
  run.setting = setting;
  run.backend = backend;
  std::unique_ptr<Simulation> sim;
  try {
    const BackendChoice choice{backend == BackendKind::cuda ? BackendChoice::Want::cuda : BackendChoice::Want::cpu, 0};
    sim = std::make_unique<Simulation>(with(setting), choice);
  } catch (const std::invalid_argument& e) {
    run.status = std::string("refused: ") + e.what();
  } catch (const InputError& e) {
    run.status = std::string("refused: ") + e.what();
  }
  if (!sim) {
    for (long k = 0; k < frames_per_run(); ++k) frame_done();
    return run;
  }
  const Scene& s = sim->scene();
  // The metrics read what the blend lays over the tissue.
  const char* film = blend_film_field(s);
  const char* stain = blend_stain_field(s);
  for (long k = 0; k < frames_per_run(); ++k) {
    FrameFields fields{s.domain.width_px, s.domain.height_px, s.domain.width_mm, s.domain.height_mm, {}, {}, {}};
    const Clock::time_point start = Clock::now();
    sim->step();
    if (film) fields.film_mm = copy_as<float>(*sim, film);
    if (stain) fields.stain = copy_as<float>(*sim, stain);
    fields.rgba = sim->copy_field("frame");
    run.frame_seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    GridFrame frame = on_grid(fields, grid_w_, grid_h_);
    if (!reference.empty()) run.errors.push_back(compare(frame, reference[std::size_t(k)]));
    if (knob_reference) run.knob_errors.push_back(compare(frame, (*knob_reference)[std::size_t(k)]));
    if (keep) keep->push_back(std::move(frame));
    frame_done();
  }
  return run;
}

double Study::finest_value(const std::string& knob) const {
  for (const KnobSweep& sweep : spec_.sweeps)
    if (knob == sweep.knob->name) return finest(*sweep.knob, sweep.values, sweep.knob->base(base_));
  return 0;
}

std::vector<StudyRun> Study::run(const std::function<void(long frames_done)>& progress) {
  long done = 0;
  const auto frame_done = [&] { progress(++done); };
  // The reference once, on the first backend asked for (both give the same bytes); then it is timed
  // and compared with itself like any setting, on each backend.
  std::vector<GridFrame> reference;
  const StudyRun first = run_one(settings_.front(), spec_.backends.front(), {}, nullptr, &reference, frame_done);
  if (first.status != "ok")
    throw InputError(no_place(), "reference",
                     "the finest settings (" + reference_description() + ") cannot run: " + first.status +
                         "; narrow the knobs' ranges");
  std::vector<StudyRun> runs(settings_.size() * spec_.backends.size());
  // Runs setting i on every backend, compared with the knob's finest frames (when kept), or keeping
  // its own frames as the knob's finest.
  std::vector<GridFrame> knob_reference;
  const auto run_setting = [&](std::size_t i, bool knob_finest) {
    for (std::size_t b = 0; b < spec_.backends.size(); ++b) {
      std::vector<GridFrame>* keep = knob_finest && b == 0 ? &knob_reference : nullptr;
      const std::vector<GridFrame>* compared = keep || knob_reference.empty() ? nullptr : &knob_reference;
      StudyRun& run = runs[i * spec_.backends.size() + b];
      run = run_one(settings_[i], spec_.backends[b], reference, compared, keep, frame_done);
      if (keep)  // the knob's finest against itself
        for (const GridFrame& frame : knob_reference) run.knob_errors.push_back(compare(frame, frame));
    }
  };
  run_setting(0, false);
  run_setting(1, false);
  // The knobs' settings come in groups (one knob after another); each group's finest runs first.
  for (std::size_t group = 2; group < settings_.size();) {
    std::size_t end = group;
    while (end < settings_.size() && settings_[end].knob == settings_[group].knob) ++end;
    const double finest = finest_value(settings_[group].knob);
    knob_reference.clear();
    for (std::size_t i = group; i < end; ++i)
      if (settings_[i].value == finest) run_setting(i, true);
    for (std::size_t i = group; i < end; ++i)
      if (settings_[i].value != finest) run_setting(i, false);
    group = end;
  }
  return runs;
}

}  // namespace bleedsim
