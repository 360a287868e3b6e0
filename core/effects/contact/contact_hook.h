#pragma once
// The tip's body in the blood, after each sub-step (core/physics/instrument.h, "contact"): counted
// under "contact".
#include <optional>
#include <vector>

#include "core/effects/particle_hook.h"
#include "core/physics/instrument.h"

namespace bleedsim {

// [contact] resolved: how near the tip a particle's centre may come (tip_body_mm).
struct ContactSettings {
  double body_mm;
};

class ContactHook final : public ParticleHook {
 public:
  ContactHook(const Scene& scene, const Resolved& resolved, Backend& backend, int capacity);
  // None: the tip's body is a few numbers of the launch.
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void act(const Scene& scene, State& state, Backend& backend, const ParticleArgs& particles, double t0,
           double t1) override;
  // act's launch, given the tip: where it is (`at`), and where it was dt_s before (its velocity;
  // none: at rest). The benchmarks call it with a tip of their own.
  void act_at(Backend& backend, const ParticleArgs& particles, const ToolSample& at,
              const std::optional<ToolSample>& before, double dt_s);

 private:
  std::vector<ToolSample> path_;  // a scripted path; empty: the stylus (State::stylus)
  InstrumentArgs args_{};         // the tip's body: the scene's, set once
};

}  // namespace bleedsim
