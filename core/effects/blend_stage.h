#pragma once
#include <cstddef>

#include "core/effects/stage.h"

namespace bleedsim {

// Each frame: the blood's fields composited over the tissue into the RGBA8 frame. Every scene
// has it: without effects the frame is the bare tissue.
class BlendStage final : public Stage {
 public:
  BlendStage(const Scene& scene, State& state, Backend& backend);
  static std::size_t bytes_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  Field& frame_;
  Buffer tissue_;        // the scene's tissue, uploaded once
  Buffer transmission_;  // the Beer–Lambert table, for scenes with a film of blood (particles)
};

}  // namespace bleedsim
