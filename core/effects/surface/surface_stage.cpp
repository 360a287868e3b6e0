#include "core/effects/surface/surface_stage.h"

namespace bleedsim {

SurfaceStage::SurfaceStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend) : Stage(kind) {
  const SurfaceMaps maps = bake_surface_maps(scene.mesh->mesh(), texture_panel(scene.domain), scene.device_gravity_mm_s2());
  Field& frame = add_field(scene, state, backend, "surface/frame");
  Field& gravity = add_field(scene, state, backend, "surface/gravity");
  backend.upload(frame.data.data(), maps.frame.data(), frame.bytes());
  backend.upload(gravity.data.data(), maps.gravity.data(), gravity.bytes());
}

MemoryParts SurfaceStage::memory_for(const Scene& scene) {
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

}  // namespace bleedsim
