#pragma once
// The tissue mesh's surface maps (docs/mesh.md): the surface stage, which every scene with a mesh
// runs (no effect's), and how the stages that measure in surface mm find its maps.
#include <string>
#include <vector>

#include "core/effects/stage_kinds.h"
#include "core/mesh/surface_bake.h"
#include "core/physics/surface.h"

namespace bleedsim {

// The texture of a scene's panel, as the bake takes it.
TexturePanel texture_panel(const Domain& domain);
// The surface maps in State, as the physics reads them; an empty map (the flat panel) without a mesh.
SurfaceMap surface_map(const Scene& scene, const State& state);
// The kind of stage it is: not an effect's, but the tissue mesh's (every scene with one runs it).
const StageKind& surface_stage_kind();

// The fields a stage that measures in surface mm reads: the surface maps, in a scene with a mesh.
std::vector<std::string> surface_fields(const Scene& scene);

}  // namespace bleedsim
