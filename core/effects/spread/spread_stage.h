#pragma once
#include <cstddef>
#include <vector>

#include "core/effects/spread/spread_tiles.h"
#include "core/effects/stage.h"
#include "core/physics/spread.h"

namespace bleedsim {

// (cuts, frame time) => spread/stain
// Each frame: the cuts' amplitudes at the frame time and the live cuts' tile table (host), then the
// stain field (backend). Cuts at the front of the list whose stains no longer change are folded,
// once, into the light they let through (SpreadSettle), so that a frame's cost follows the cuts
// still growing, not every cut made; and each pixel multiplies in only the live cuts its tile
// lists, so that its cost follows the cuts that overlap it.
class SpreadStage final : public Stage {
 public:
  SpreadStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  // The box of pixels that holds every pixel these cuts can stain.
  SpreadSettle settle_box(const Scene& scene, const SpreadCut* cuts, int count) const;

  Field& stain_;
  Buffer cuts_;      // SpreadUpload's block: the cuts to settle, the live cuts, their tile table; grows
  Buffer settled_;   // float per pixel: the light the settled cuts let through
  std::size_t settled_count_ = 0;  // cuts [0, settled_count_) of the list are folded into settled_
  double reach_per_mm_;            // spread_reach_per_mm
  std::vector<SpreadCut> host_;
  SpreadUpload upload_;
  std::vector<unsigned char> on_device_;  // the block as last copied into cuts_
};

}  // namespace bleedsim
