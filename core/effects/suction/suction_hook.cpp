#include "core/effects/suction/suction_hook.h"

#include <cmath>

#include "core/effects/particles/particle_model.h"

namespace bleedsim {
namespace {

std::size_t candidates_bytes(int capacity) {
  return std::size_t(capacity) * sizeof(std::uint64_t) + sizeof(std::uint64_t);
}

// The tip of the scene's instrument at t: its scripted path, which ends at its last point, or
// the stylus, which stays where it was last seen.
std::optional<ToolSample> instrument_at(const Scene& scene, const std::vector<ToolSample>& path, const State& state,
                                        double t_s) {
  return scene.tips.empty() ? tool_at(state.stylus, t_s, true) : tool_at(path, t_s, false);
}

}  // namespace

Instrument::Instrument(const Scene& scene, Backend& backend, int capacity)
    : path_(scripted_tool(scene.tips)), contact_(scene.contact.has_value()) {
  if (scene.contact)
    args_.tip.body_mm = float(scene.contact->tip_radius_mm + scene.particles->diameter_mm / 2.0);
  if (!scene.suction) return;
  args_.tip.reach_sq = float(scene.suction->radius_mm * scene.suction->radius_mm);
  particles_per_step_ =
      scene.suction->max_flow_mm3_per_s / particle_steps_per_s(scene) / scene.particles->particle_volume_mm3;
  scratch_ = backend.allocate(candidates_bytes(capacity));
  args_.candidates = scratch_.as<std::uint64_t>();
  args_.candidate_count = reinterpret_cast<std::uint32_t*>(args_.candidates + capacity);
  const std::uint64_t none = 0;
  backend.upload(args_.candidate_count, &none, sizeof none);
}

MemoryParts Instrument::memory_for(const Scene& scene) {
  if (!scene.suction) return {};
  return {{"particles.capacity", "the suction's candidates", Count(candidates_bytes(scene.particles->capacity))}};
}

void Instrument::act(const Scene& scene, const State& state, Backend& backend, const ParticleArgs& particles,
                     double t0, double t1) {
  const std::optional<ToolSample> at = instrument_at(scene, path_, state, t1);
  if (!at) return;
  // The quota is the whole particles the flow allows by the end of this step less those it allowed
  // before: over k steps with the suction on, floor(k · flow · dt / V) in all, taken or not.
  std::uint32_t quota = 0;
  if (scene.suction && at->suction) {
    const double k = double(suction_steps_++);
    quota = std::uint32_t(std::floor((k + 1.0) * particles_per_step_) - std::floor(k * particles_per_step_));
  }
  act_at(backend, particles, *at, instrument_at(scene, path_, state, t0), t1 - t0, quota);
}

void Instrument::act_at(Backend& backend, const ParticleArgs& particles, const ToolSample& at,
                        const std::optional<ToolSample>& before, double dt_s, std::uint32_t quota) {
  if (particles.live_count == 0) return;
  args_.model = particles.model;
  args_.arrays = particles.arrays;
  args_.first_live_slot = particles.first_live_slot;
  args_.live_count = particles.live_count;
  args_.quota = quota;
  args_.tip.x_mm = float(at.x_mm);
  args_.tip.y_mm = float(at.y_mm);
  args_.tip.vx_mm_s = before ? float((at.x_mm - before->x_mm) / dt_s) : 0.0f;
  args_.tip.vy_mm_s = before ? float((at.y_mm - before->y_mm) / dt_s) : 0.0f;
  if (quota > 0) backend.run("suction", InstrumentPhase::aspirate, args_);
  if (contact_ && at.contact) backend.run("contact", InstrumentPhase::contact, args_);
}

std::vector<float> suction_sweep(const Scene& scene, const State& state, double t0_s, double t1_s) {
  std::vector<float> segments;
  if (!scene.suction) return segments;
  const std::vector<ToolSample> path = scripted_tool(scene.tips);
  const std::vector<ToolSample>& samples = scene.tips.empty() ? state.stylus : path;
  // The tip moves in straight lines between samples: its path over [t0, t1] is the polyline through
  // its places at t0, at each sample between, and at t1.
  std::vector<double> times{t0_s};
  for (const ToolSample& s : samples)
    if (s.t_s > t0_s && s.t_s < t1_s) times.push_back(s.t_s);
  times.push_back(t1_s);
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const std::optional<ToolSample> a = instrument_at(scene, path, state, times[i]);
    const std::optional<ToolSample> b = instrument_at(scene, path, state, times[i + 1]);
    if (!a || !b || !a->suction || !b->suction) continue;
    for (const double v : {a->x_mm, a->y_mm, b->x_mm, b->y_mm}) segments.push_back(float(v));
  }
  return segments;
}

}  // namespace bleedsim
