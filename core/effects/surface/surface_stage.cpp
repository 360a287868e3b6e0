#include "core/effects/surface/surface_stage.h"

#include "core/effects/particles/particle_model.h"
#include "core/effects/stage.h"

namespace bleedsim {

// () => surface/frame, surface/gravity
// Once, in scenes with a tissue mesh: the surface maps baked from the mesh (core/mesh/surface_bake.h)
// and uploaded; every frame after, nothing. The particles, the splat and the spread read them.
class SurfaceStage final : public Stage {
 public:
  SurfaceStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void run(const Scene&, State&, Backend&) override {}
};

SurfaceStage::SurfaceStage(const StageKind& kind, const Scene& scene, const Resolved&, State& state, Backend& backend)
    : Stage(kind) {
  const SurfaceMaps maps =
      bake_surface_maps(scene.mesh->mesh(), texture_panel(scene.domain), device_gravity_mm_s2(scene));
  Field& frame = add_field(scene, state, backend, "surface/frame");
  Field& gravity = add_field(scene, state, backend, "surface/gravity");
  backend.upload(frame.data.data(), maps.frame.data(), frame.bytes());
  backend.upload(gravity.data.data(), maps.gravity.data(), gravity.bytes());
}

MemoryParts SurfaceStage::memory_for(const Scene& scene, const Resolved&) {
  return {scene.domain.memory((kSurfaceFrameChannels + kSurfaceGravityChannels) * sizeof(float))};
}

TexturePanel texture_panel(const Domain& d) { return {d.width_px, d.height_px, d.width_mm, d.height_mm}; }

SurfaceMap surface_map(const Scene& scene, const State& state) {
  SurfaceMap map;
  if (!scene.mesh) return map;
  map.frame = state.require("surface/frame").data.as<const float>();
  map.gravity = state.require("surface/gravity").data.as<const float>();
  map.grid = scene.domain.grid();
  return map;
}

std::vector<std::string> surface_fields(const Scene& scene) {
  if (!scene.mesh) return {};
  return {"surface/frame", "surface/gravity"};
}

const StageKind& surface_stage_kind() {
  static const StageKind kind{
      "surface", "tissue", [](const Scene& s) { return s.mesh != nullptr; },
      {on_request(image_field("surface/frame", ElementType::f32, kSurfaceFrameChannels, "mm/mm",
                              "the tissue mesh's map from panel to surface mm at each texel, (a, b, c): a panel step "
                              "(dx, dy) goes (a dx + b dy, c dy) on the surface; and 1 where a triangle covers the "
                              "texel")),
       on_request(image_field("surface/gravity", ElementType::f32, kSurfaceGravityChannels, "mm/s²",
                              "gravity along the tissue mesh's surface at each texel, in the frame of surface/frame"))},
      no_fields, SurfaceStage::memory_for, make_stage<SurfaceStage>};
  return kind;
}

}  // namespace bleedsim
