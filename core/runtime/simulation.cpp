#include "core/runtime/simulation.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/runtime/memory.h"
#include "core/effects/particle_model.h"
#include "core/haptics/trace_replay.h"

namespace bleedsim {
namespace {

void check_cut(const Cut& cut) {
  if (!std::isfinite(cut.x_mm) || !std::isfinite(cut.y_mm) || !std::isfinite(cut.start_s) ||
      !std::isfinite(cut.radius_mm) || !std::isfinite(cut.growth_per_s) || !std::isfinite(cut.rate_per_s) ||
      !std::isfinite(cut.bleed_s))
    throw std::invalid_argument("a cut's position, start, radius, growth, rate and bleeding time must be finite");
  if (!(cut.radius_mm > 0) || !(cut.growth_per_s > 0))
    throw std::invalid_argument("a cut's radius and growth rate must be positive");
  if (cut.rate_per_s < 0 || cut.rate_per_s > kMaxParticleRate || cut.bleed_s < 0)
    throw std::invalid_argument("a cut's particle rate must be between 0 and 1e8 per second and its "
                                "bleeding time not negative");
}

void check_consistent(const Scene& scene) {
  const Domain& d = scene.domain;
  if (d.width_px <= 0 || d.height_px <= 0 || !(d.width_mm > 0) || !(d.height_mm > 0))
    throw std::invalid_argument("scene domain must have positive sizes in pixels and mm");
  if (!(scene.frame_rate_hz > 0) || !std::isfinite(scene.frame_rate_hz))
    throw std::invalid_argument("scene frame rate must be positive and finite");
  // frame_count() is an int: the same limit the scenario parser sets.
  const double frames = scene.duration_s * scene.frame_rate_hz;
  if (!(frames >= 0.5) || !(frames <= 1e7))
    throw std::invalid_argument("scene duration × frame rate must give 1 to 10,000,000 frames");
  if (scene.tissue.width != d.width_px || scene.tissue.height != d.height_px ||
      scene.tissue.rgba.size() != std::size_t(d.pixel_count()) * 4)
    throw std::invalid_argument("scene tissue must be a width_px × height_px RGBA8 image");
  for (const Cut& cut : scene.cuts) check_cut(cut);
  if (scene.particles) {
    const ParticleParams& p = *scene.particles;
    if (p.capacity < 1 || !(p.diameter_mm > 0) || p.max_per_cell < 1 || p.substeps < 1 ||
        !(p.lifetime_s > 0) || !(p.fade_s > 0) || !(p.stiffness_per_s2 > 0) || !(p.damping_per_s >= 0) ||
        !(p.drag_per_s >= 0) || !(p.max_speed_mm_s > 0) || !(p.particle_volume_mm3 > 0) ||
        !(p.splat_radius_mm >= 0) || (p.cell_mm != 0 && !(p.cell_mm >= p.diameter_mm)))
      throw std::invalid_argument("scene particle parameters out of range (see docs/particles.md)");
    const SettingsProblem problem = particle_settings_problem(scene);
    if (!problem.key.empty()) throw std::invalid_argument(problem.key + ": " + problem.message);
  }
  if (scene.haptics) {
    const HapticParams& h = *scene.haptics;
    if (!std::isfinite(h.surface_z_mm) || !std::isfinite(h.origin_x_mm) || !std::isfinite(h.origin_y_mm) ||
        !(h.scale > 0) || !std::isfinite(h.scale) || !(h.stiffness_N_per_m > 0) || !(h.damping_Ns_per_m >= 0) ||
        !(h.max_force_N > 0) || !(h.max_force_N <= kFalconMaxForce_N) || h.cut_buttons == 0 ||
        !(h.cut_spacing_mm > 0))
      throw std::invalid_argument("scene haptic parameters out of range (see docs/haptics.md)");
    const PassivityProblem problem = passivity_problem(h);
    if (!problem.key.empty()) throw std::invalid_argument(problem.key + ": " + problem.message);
  }
  if (scene.trace && (!scene.haptics || scene.trace->samples.empty()))
    throw std::invalid_argument("a scene's trace needs [haptics] to replay it through, and samples");
  if (scene.blur) {
    const BlurParams& b = *scene.blur;
    if (!scene.particles) throw std::invalid_argument("a scene's blur needs particles to blur");
    if ((b.downsample != 1 && b.downsample != 2 && b.downsample != 4) || b.radius_px < 0 || b.radius_px > 64 ||
        !(b.sigma_px > 0) || !(b.sigma_px <= 64))
      throw std::invalid_argument("scene blur parameters out of range (downsample 1, 2 or 4; radius 0-64; sigma (0, 64])");
  }
}

// The fields must fit where the backend computes, and a host copy of them must fit for reading
// frames out. Checked before anything is allocated, so a too-large scene fails at once.
void check_fits(const Scene& scene, const Backend& backend) {
  const std::size_t on_backend = Pipeline::backend_bytes(scene);
  if (backend.kind() == BackendKind::cpu) {
    require_room(scene, 2 * on_backend, available_host_memory(), "host");
  } else {
    require_room(scene, on_backend, backend.memory_available(), "device");
    require_room(scene, on_backend, available_host_memory(), "host");
  }
}

}  // namespace

Simulation::Simulation(Scene scene, const BackendChoice& choice) : scene_(std::move(scene)) {
  check_consistent(scene_);
  SelectedBackend selected = select_backend(choice);
  backend_ = std::move(selected.backend);
  backend_reason_ = std::move(selected.why);
  check_fits(scene_, *backend_);
  state_.cuts = scene_.cuts;
  pipeline_ = std::make_unique<Pipeline>(scene_, state_, *backend_);
  if (scene_.trace) haptics_.emplace(scene_);
}

Simulation::~Simulation() = default;

void Simulation::add_cut(const Cut& cut) {
  check_cut(cut);
  state_.cuts.push_back(cut);
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
    if (step.cut) state_.cuts.push_back(*step.cut);
    tick_seconds_.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    frame_ticks_.push_back(step.record);
  }
}

void Simulation::step() {
  replay_haptic_ticks();
  pipeline_->run_frame(scene_, state_, *backend_);
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
