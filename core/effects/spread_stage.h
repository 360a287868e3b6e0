#pragma once
#include <cstddef>
#include <vector>

#include "core/effects/stage.h"
#include "core/physics/spread.h"

namespace bleedsim {

// (cuts, frame time) => spread/stain
// Each frame: the cuts' amplitudes at the frame time (host), then the stain field (backend). Cuts
// at the front of the list whose stains no longer change are folded, once, into the light they let
// through (SpreadSettle), so that a frame's cost follows the cuts still growing, not every cut made.
class SpreadStage final : public Stage {
 public:
  SpreadStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  // The box of pixels that holds every pixel these cuts can stain.
  SpreadSettle settle_box(const Scene& scene, const SpreadCut* cuts, int count) const;

  Field& stain_;
  Buffer cuts_;      // SpreadCut per cut to settle, then per live cut, uploaded each frame; grows
  Buffer settled_;   // float per pixel: the light the settled cuts let through
  std::size_t settled_count_ = 0;  // cuts [0, settled_count_) of the list are folded into settled_
  double reach_per_mm_ = 1.0;      // panel mm a surface mm may span (1 on the flat panel)
  std::vector<SpreadCut> host_;
};

}  // namespace bleedsim
