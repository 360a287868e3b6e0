#pragma once
#include <cstddef>

#include "core/physics/splat.h"
#include "core/effects/stage.h"

namespace bleedsim {

// (particles/position, particles/age) => splat/thickness
// Each frame, in scenes with particles: the live particles splatted into a film of blood, in mm.
class SplatStage final : public Stage {
 public:
  SplatStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  SplatArgs args_{};
  Buffer units_;   // the fixed-point sum
  Buffer stamps_;  // its tiles' stamps
};

// The splat's constants for a scene with particles, on its panel's pixels.
SplatModel make_splat_model(const ParticleParams& params, const Domain& domain);

}  // namespace bleedsim
