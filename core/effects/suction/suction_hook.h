#pragma once
// The instrument's part of each particle sub-step (core/physics/instrument.h): where its tip is,
// how many particles its suction may take, and the launches, counted under "suction" and
// "contact". The particle stage makes one only for a scene with [suction] or [contact].
#include <cstdint>
#include <optional>
#include <vector>

#include "core/physics/instrument.h"
#include "core/runtime/backend.h"
#include "core/runtime/memory.h"
#include "core/scene/state.h"

namespace bleedsim {

class Instrument {
 public:
  Instrument(const Scene& scene, Backend& backend, int capacity);
  // With suction, the candidates' keys: a slot's worth each.
  static MemoryParts memory_for(const Scene& scene);

  // After the sub-step over [t0, t1] has moved the particles: suction, then contact, at the tip's
  // place at t1. Particles it aspirates are counted in the arrays' fates.
  void act(const Scene& scene, const State& state, Backend& backend, const ParticleArgs& particles, double t0,
           double t1);
  // act's launches, given the tip: where it is (`at`; in contact, it parts the blood in a scene
  // with [contact]), where it was dt_s before (its velocity; none: at rest), and how many particles
  // the suction may take (0: it does not suck; more only in a scene with [suction]). The benchmarks
  // call it with a tip and a quota of their own.
  void act_at(Backend& backend, const ParticleArgs& particles, const ToolSample& at,
              const std::optional<ToolSample>& before, double dt_s, std::uint32_t quota);
  // max_flow × dt / particle volume: the suction's quota a step on average (0 without suction).
  double particles_per_step() const { return particles_per_step_; }

 private:
  std::vector<ToolSample> path_;      // a scripted path; empty: the stylus (State::stylus)
  bool contact_ = false;              // the scene's tip parts the blood
  double particles_per_step_ = 0.0;   // max_flow × dt / particle volume: the suction's quota a step
  std::uint64_t suction_steps_ = 0;   // sub-steps with the suction on so far
  Buffer scratch_;                    // with suction: the candidates' keys, then their count
  InstrumentArgs args_{};             // the tip's reach and body: the scene's, set once
};

// Where the suction's tip swept over the panel between t0 and t1, as segments (x0, y0, x1, y1)
// in mm: what the trail stage dries under it. None when the scene has no suction.
std::vector<float> suction_sweep(const Scene& scene, const State& state, double t0_s, double t1_s);

}  // namespace bleedsim
