#pragma once
#include <cstddef>
#include <vector>

#include "core/effects/stage.h"
#include "core/physics/spread.h"

namespace bleedsim {

// (cuts, frame time) => spread/stain
// Each frame: the cuts' amplitudes at the frame time (host), then the stain field (backend).
class SpreadStage final : public Stage {
 public:
  SpreadStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  Field& stain_;
  Buffer cuts_;  // SpreadCut per active cut, uploaded each frame; grows with the cut list
  std::vector<SpreadCut> active_;
};

}  // namespace bleedsim
