#pragma once
#include "core/effects/stage.h"
#include "core/mesh/surface_bake.h"
#include "core/physics/surface.h"

namespace bleedsim {

// () => surface/frame, surface/gravity
// Once, in scenes with a tissue mesh: the surface maps baked from the mesh (core/mesh/surface_bake.h)
// and uploaded; every frame after, nothing. The particles, the splat and the spread read them.
class SurfaceStage final : public Stage {
 public:
  SurfaceStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene&, State&, Backend&) override {}
};

// The texture of a scene's panel, as the bake takes it.
TexturePanel texture_panel(const Domain& domain);
// The surface maps in State, as the physics reads them; an empty map (the flat panel) without a mesh.
SurfaceMap surface_map(const Scene& scene, const State& state);
// The fields a stage that measures in surface mm reads: the surface maps, in a scene with a mesh.
std::vector<std::string> surface_fields(const Scene& scene);

}  // namespace bleedsim
