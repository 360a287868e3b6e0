#include "core/simulation/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/effects/cuts.h"
#include "core/effects/effect_list.h"
#include "core/haptics/trace_replay.h"
#include "core/runtime/memory.h"
#include "core/simulation/scene_check.h"

namespace bleedsim {
namespace {

// The fields must fit where the backend computes, and a host copy of them must fit for reading
// frames out. Checked before anything is allocated, so a too-large scene fails at once.
void check_fits(const Scene& scene, const Resolved& resolved, const Backend& backend) {
  const MemoryParts on_backend = Pipeline::memory(scene, resolved);
  if (backend.kind() == BackendKind::cpu) {
    require_memory(times(on_backend, 2), available_host_memory(), "host");
  } else {
    require_memory(on_backend, backend.memory_available(), "device");
    require_memory(on_backend, available_host_memory(), "host");
  }
}

// The stylus as the instrument: its tip where the tick found it over the panel, in contact when it
// touches the tissue, with the buttons the tick found held.
ToolSample stylus_sample(const HapticTick& tick) {
  return {tick.t_s, tick.panel_mm.x(), tick.panel_mm.y(), tick.contact, tick.buttons};
}

}  // namespace

Simulation::Simulation(Scene scene, const BackendChoice& choice) : scene_(std::move(scene)) {
  if (const ParamProblem problem = scene_problem(scene_)) throw std::invalid_argument(problem.text());
  SelectedBackend selected = select_backend(choice);
  backend_ = std::move(selected.backend);
  backend_reason_ = std::move(selected.why);
  resolved_ = resolve(scene_);
  check_fits(scene_, resolved_, *backend_);
  for (const Cut& cut : scene_.cuts) state_.cuts.push_back(cut_as_made(scene_, cut));
  pipeline_ = std::make_unique<Pipeline>(scene_, resolved_, state_, *backend_);
  if (scene_.trace) haptics_.emplace(scene_);
}

Simulation::~Simulation() = default;

void Simulation::add_cut(const Cut& cut) {
  if (const ParamProblem problem = check_params(cut_table(), cut, scene_)) throw std::invalid_argument(problem.text());
  state_.cuts.push_back(cut_as_made(scene_, cut));
}

void Simulation::add_stylus_sample(const ToolSample& sample) {
  if (!scene_.haptics || scene_.trace)
    throw std::invalid_argument("stylus samples: this scene's stylus is " +
                                std::string(scene_.trace ? "its trace's" : "absent (it declares no [haptics])"));
  if (!std::isfinite(sample.t_s) || !std::isfinite(sample.x_mm) || !std::isfinite(sample.y_mm))
    throw std::invalid_argument("stylus samples: t_s, x_mm and y_mm must be finite");
  if (!state_.stylus.empty() && !(sample.t_s > state_.stylus.back().t_s))
    throw std::invalid_argument("stylus samples: each must be later than the one before");
  state_.stylus.push_back(sample);
}

void Simulation::replay_haptic_ticks() {
  using Clock = std::chrono::steady_clock;
  frame_ticks_.clear();
  tick_seconds_.clear();
  if (!haptics_) return;
  const std::int64_t end = scene_.haptic_ticks_through_frame(state_.frames_done);
  while (haptics_->ticks_done() < end) {
    const Clock::time_point start = Clock::now();
    HapticStep step = haptics_->tick(trace_sample_at_tick(*scene_.trace, haptics_->ticks_done()));
    if (step.cut) state_.cuts.push_back(cut_as_made(scene_, *step.cut));
    state_.stylus.push_back(stylus_sample(step.record));
    tick_seconds_.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    frame_ticks_.push_back(step.record);
  }
}

void Simulation::step() {
  replay_haptic_ticks();
  pipeline_->run_frame(scene_, state_, *backend_);
  // The stylus's samples up to this frame's end are done with but the last, where it stays.
  const double end_s = scene_.frame_time_s(state_.frames_done);
  std::vector<ToolSample>& stylus = state_.stylus;
  const auto after = std::upper_bound(stylus.begin(), stylus.end(), end_s,
                                      [](double t, const ToolSample& s) { return t < s.t_s; });
  if (after - stylus.begin() > 1) stylus.erase(stylus.begin(), after - 1);
  ++state_.frames_done;
}

double Simulation::time_s() const {
  return state_.frames_done == 0 ? 0.0 : scene_.frame_time_s(state_.frames_done - 1);
}

std::vector<std::string> Simulation::field_names() const {
  std::vector<std::string> names;
  for (const Field& field : state_.fields) names.push_back(field.name);
  return names;
}

FieldView Simulation::field(const std::string& name) const {
  const Field* found = state_.find(name);
  if (!found) throw std::out_of_range("this scene has no field '" + name + "'");
  return FieldView{found, found->data.data(), backend_->kind()};
}

std::vector<std::uint8_t> Simulation::copy_field(const std::string& name) const {
  std::vector<std::uint8_t> bytes(field(name).field->bytes());
  copy_field(name, bytes.data());
  return bytes;
}

void Simulation::copy_field(const std::string& name, void* host_destination) const {
  const FieldView view = field(name);
  backend_->download(host_destination, view.data, view.field->bytes());
}

}  // namespace bleedsim
