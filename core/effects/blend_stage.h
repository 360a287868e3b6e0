#pragma once
#include <cstddef>

#include "core/effects/stage.h"
#include "core/physics/blend.h"

namespace bleedsim {

// (tissue, spread/stain, the film: blur/thickness or splat/thickness) => frame
// Each frame: the blood's fields composited over the tissue into the RGBA8 frame. Every scene
// has it: without effects the frame is the bare tissue.
class BlendStage final : public Stage {
 public:
  BlendStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  Buffer tissue_;        // the scene's tissue, uploaded once
  Buffer transmission_;  // the Beer–Lambert table, for scenes with a film of blood
  BlendPixel work_{};
};

// What the blend lays over the tissue, by field name, or null where the scene has none of it: the
// stain, spread/stain with [spread]; the film of blood, blur/thickness with [blur], else
// splat/thickness with [particles].
const char* blend_stain_field(const Scene& scene);
const char* blend_film_field(const Scene& scene);

}  // namespace bleedsim
