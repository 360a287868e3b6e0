#pragma once
#include <cstddef>
#include <vector>

#include "core/physics/blur.h"
#include "core/effects/stage.h"

namespace bleedsim {

// (splat/thickness) => blur/thickness
// Each frame, in scenes with [blur]: the film downsampled, blurred across and down, and upsampled,
// which the blend then lays over the tissue instead of the raw film.
class BlurStage final : public Stage {
 public:
  BlurStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  BlurArgs args_{};
  Buffer weights_, low_, across_;
};

// The Gaussian's taps for a radius and sigma (in downsampled pixels), in double, normalised to a
// sum of 1 and rounded once to float.
std::vector<float> gaussian_weights(int radius, double sigma);

}  // namespace bleedsim
