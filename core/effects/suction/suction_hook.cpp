#include "core/effects/suction/suction_hook.h"

#include <cmath>
#include <cstdio>
#include <memory>

#include "core/effects/effect.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/suction/suction_params.h"
#include "core/effects/tips.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// The suction is on where the tip touches the tissue with one of its buttons held.
bool sucking(const ToolSample& tip, std::uint8_t buttons) { return tip.contact && (tip.buttons & buttons) != 0; }

std::size_t candidates_bytes(int capacity) {
  return std::size_t(capacity) * sizeof(std::uint64_t) + sizeof(std::uint64_t);
}

void resolve_suction(const Scene& scene, Resolved& resolved) {
  const double steps_per_s = resolved.get<ParticleSettings>().steps_per_s;
  resolved.set(SuctionSettings{scene.effects.get<SuctionParams>().max_flow_mm3_per_s / steps_per_s /
                               scene.effects.get<ParticleParams>().particle_volume_mm3});
}

std::string describe_suction(const Scene& scene, const Resolved& resolved, const RunOutline&) {
  const SuctionParams& s = scene.effects.get<SuctionParams>();
  std::string line = "  suction    " + instrument_words(scene) + ": reach " + format_significant(s.radius_mm, 6) +
                     " mm, up to " + format_significant(s.max_flow_mm3_per_s, 6) + " mm³/s (" +
                     format_significant(resolved.get<SuctionSettings>().particles_per_step, 3) +
                     " particles a sub-step)";
  if (scene.tips.empty()) {
    char buttons[8];
    std::snprintf(buttons, sizeof buttons, "0x%x", unsigned(s.buttons));
    line += std::string(", in contact with a button of ") + buttons + " held";
  }
  return line + "\n";
}

}  // namespace

SuctionHook::SuctionHook(const Scene& scene, const Resolved& resolved, Backend& backend, int capacity)
    : path_(scripted_tool(scene.tips)),
      buttons_(scene.effects.get<SuctionParams>().buttons),
      particles_per_step_(resolved.get<SuctionSettings>().particles_per_step),
      scratch_(backend.allocate(candidates_bytes(capacity))) {
  const double reach_mm = scene.effects.get<SuctionParams>().radius_mm;
  args_.tip.reach_sq = float(reach_mm * reach_mm);
  args_.candidates = scratch_.as<std::uint64_t>();
  args_.candidate_count = reinterpret_cast<std::uint32_t*>(args_.candidates + capacity);
  const std::uint64_t none = 0;
  backend.upload(args_.candidate_count, &none, sizeof none);
}

MemoryParts SuctionHook::memory_for(const Scene& scene, const Resolved&) {
  return {{"particles.capacity", "the suction's candidates",
           Count(candidates_bytes(scene.effects.get<ParticleParams>().capacity))}};
}

void SuctionHook::act(const Scene& scene, State& state, Backend& backend, const ParticleArgs& particles, double,
                      double t1) {
  const std::optional<ToolSample> at = instrument_at(scene, path_, state, t1);
  if (!at || !sucking(*at, buttons_)) return;
  // The quota is the whole particles the flow allows by the end of this step less those it allowed
  // before: over k steps with the suction on, floor(k · flow · dt / V) in all, taken or not.
  const double k = double(suction_steps_++);
  act_at(backend, particles, *at,
         std::uint32_t(std::floor((k + 1.0) * particles_per_step_) - std::floor(k * particles_per_step_)));
}

void SuctionHook::act_at(Backend& backend, const ParticleArgs& particles, const ToolSample& at, std::uint32_t quota) {
  if (particles.live_count == 0 || quota == 0) return;
  args_.model = particles.model;
  args_.arrays = particles.arrays;
  args_.first_live_slot = particles.first_live_slot;
  args_.live_count = particles.live_count;
  args_.quota = quota;
  args_.tip.x_mm = float(at.x_mm);
  args_.tip.y_mm = float(at.y_mm);
  backend.run("suction", args_);
}

std::vector<float> suction_sweep(const Scene& scene, const State& state, double t0_s, double t1_s) {
  std::vector<float> segments;
  const SuctionParams* suction = scene.effects.find<SuctionParams>();
  if (!suction) return segments;
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
    if (!a || !b || !sucking(*a, suction->buttons) || !sucking(*b, suction->buttons)) continue;
    for (const double v : {a->x_mm, a->y_mm, b->x_mm, b->y_mm}) segments.push_back(float(v));
  }
  return segments;
}

const Effect<SuctionParams>& suction_effect() {
  static const Effect<SuctionParams> row = [] {
    Effect<SuctionParams> e{suction_table};
    e.hooks = {{"suction", SuctionHook::memory_for, make_hook<SuctionHook>}};
    e.resolve = resolve_suction;
    e.describe = describe_suction;
    return e;
  }();
  return row;
}

}  // namespace bleedsim
