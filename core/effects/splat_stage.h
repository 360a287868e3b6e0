#pragma once
#include <cstddef>

#include "core/physics/splat.h"
#include "core/effects/stage.h"

namespace bleedsim {

// Each frame, in scenes with particles: the live particles splatted into a film of blood
// (splat/thickness, mm), read from the particle stage's fields.
class SplatStage final : public Stage {
 public:
  SplatStage(const Scene& scene, State& state, Backend& backend);
  static std::size_t bytes_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  SplatArgs args_{};
  Buffer units_;  // the fixed-point sum
};

// The splat's constants for a scene with particles.
SplatModel make_splat_model(const ParticleParams& params);

}  // namespace bleedsim
