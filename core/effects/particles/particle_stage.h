#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "core/effects/suction/suction_hook.h"
#include "core/effects/particles/particle_accounting.h"
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
  // Every step of this frame planned on the host (emission, live ranges, accounting), before any runs.
  void plan_frame(const Scene& scene, const State& state, Backend& backend);
  void plan_emission(const Scene& scene, const State& state, std::uint64_t step, ParticleStep& planned);
  void live_range(std::uint32_t& first_live_slot, int& live_count) const;

  ParticleArgs args_{};  // the model and arrays; a step's own arguments are in steps_
  Field* counts_ = nullptr;  // the accounting, uploaded each frame (aspirated only with [suction])
  ParticleAccounting accounting_;
  int substeps_;                    // physics steps per frame
  Buffer scratch_;                  // every array of ParticleArrays that is not a field
  std::vector<ParticleStep> steps_;  // this frame's
  std::vector<Emitter> emitters_;    // this frame's steps' emitters, in step order
  Buffer plan_;                      // the backend's copy of both; grows with the emitters
  std::unique_ptr<TwinCache> graph_;  // the backend's (CUDA: the steps' graph)
  std::optional<Instrument> instrument_;  // with [suction] or [contact]
};

}  // namespace bleedsim
