#pragma once
// The suction, after each sub-step (core/physics/instrument.h, "aspirate"): its quota of whole
// particles from its flow, and its launches, counted under "suction".
#include <cstdint>
#include <vector>

#include "core/effects/particle_hook.h"
#include "core/physics/instrument.h"

namespace bleedsim {

// [suction] resolved: max_flow × dt / particle volume, the particles its flow takes a sub-step on
// average.
struct SuctionSettings {
  double particles_per_step;
};

class SuctionHook final : public ParticleHook {
 public:
  SuctionHook(const Scene& scene, const Resolved& resolved, Backend& backend, int capacity);
  // The candidates' keys: a slot's worth each.
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void act(const Scene& scene, State& state, Backend& backend, const ParticleArgs& particles, double t0,
           double t1) override;
  // act's launches, given the tip where it is (`at`) and how many particles it may take (0: none).
  // The benchmarks call it with a tip and a quota of their own.
  void act_at(Backend& backend, const ParticleArgs& particles, const ToolSample& at, std::uint32_t quota);

 private:
  std::vector<ToolSample> path_;     // a scripted path; empty: the stylus (State::stylus)
  std::uint8_t buttons_;             // the grip buttons that turn it on, in contact
  double particles_per_step_;        // SuctionSettings'
  std::uint64_t suction_steps_ = 0;  // sub-steps with the suction on so far
  Buffer scratch_;                   // the candidates' keys, then their count
  InstrumentArgs args_{};            // the tip's reach: the scene's, set once
};

// Where the suction's tip swept over the panel between t0 and t1, as segments (x0, y0, x1, y1)
// in mm: what the trail stage dries under it. None when the scene has no suction.
std::vector<float> suction_sweep(const Scene& scene, const State& state, double t0_s, double t1_s);

}  // namespace bleedsim
