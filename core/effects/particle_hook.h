#pragma once
// A hook in the particle step: an effect that acts on the particles between one sub-step's
// integration and the next (the suction, the tip's body in the blood). The particle stage makes
// the hooks its scene declares (make_particle_hooks, from the list of effects) and runs a frame's
// sub-steps one at a time when it has any.
#include <memory>
#include <vector>

#include "core/effects/resolved.h"
#include "core/physics/particles.h"
#include "core/runtime/backend.h"
#include "core/runtime/memory.h"
#include "core/scene/state.h"

namespace bleedsim {

class ParticleHook {
 public:
  virtual ~ParticleHook() = default;
  // After the sub-step over [t0, t1] has moved the particles (`particles` as the integration
  // left them). Its launches are counted under its kind's name. Like a stage, it may change State
  // (a hook that seals a wound would end the cut's bleeding; the frame's emission is planned, so
  // from the next frame on).
  virtual void act(const Scene& scene, State& state, Backend& backend, const ParticleArgs& particles, double t0,
                   double t1) = 0;
};

// What an effect of this kind registers (Effect::hooks).
struct HookKind {
  const char* name;  // its launches are counted under it
  MemoryParts (*memory_for)(const Scene&, const Resolved&);
  std::unique_ptr<ParticleHook> (*make)(const Scene&, const Resolved&, Backend&, int capacity);
};

// How a row builds its hook H: H(scene, resolved, backend, capacity).
template <class H>
std::unique_ptr<ParticleHook> make_hook(const Scene& scene, const Resolved& resolved, Backend& backend, int capacity) {
  return std::make_unique<H>(scene, resolved, backend, capacity);
}

// The hooks of the effects this scene declares, in the list's order, and their memory.
std::vector<std::unique_ptr<ParticleHook>> make_particle_hooks(const Scene& scene, const Resolved& resolved,
                                                               Backend& backend, int capacity);
MemoryParts particle_hooks_memory(const Scene& scene, const Resolved& resolved);

}  // namespace bleedsim
