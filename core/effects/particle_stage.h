#pragma once
#include <cstddef>
#include <optional>
#include <vector>

#include "core/effects/instrument.h"
#include "core/effects/particle_accounting.h"
#include "core/physics/particles.h"
#include "core/effects/stage.h"

namespace bleedsim {

// (cuts, instrument, particles/position, velocity, age) => particles/position, velocity, age, accounting
// Each frame: `substeps` physics steps (emit, bin, collide, integrate, and the instrument's suction
// and contact in a scene with them), then the accounting recorded. The ring buffer's state is in fields, so it is hashed, compared and written like any
// other output.
class ParticleStage final : public Stage {
 public:
  ParticleStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  // An upper bound: the CUDA sort's scratch depends on the device.
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  void emit(const Scene& scene, const State& state, Backend& backend, std::uint64_t step);
  // Points the step at the live particles, from the accounting (the ids in [oldest alive, emitted)).
  void track_live_particles();

  ParticleArgs args_{};
  Field* counts_ = nullptr;  // the accounting, uploaded each frame (aspirated only with [suction])
  ParticleAccounting accounting_;
  int substeps_;              // physics steps per frame
  Buffer scratch_;            // every array of ParticleArrays that is not a field
  Buffer emitters_;           // this step's Emitters, uploaded; grows with the cut list
  std::vector<Emitter> new_;  // host side of emitters_
  std::optional<Instrument> instrument_;  // with [suction] or [contact]
};

}  // namespace bleedsim
