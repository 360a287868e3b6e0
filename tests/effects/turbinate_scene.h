#pragma once
// The turbinate (scenarios/meshes/turbinate.obj) as a test scene's tissue: its texture stretches a
// stain's reach 0.6 to 1.7 times across the panel.
#include <memory>
#include <utility>

#include "core/effects/particles/particle_model.h"
#include "core/effects/surface/surface_stage.h"
#include "core/io/mesh_obj.h"
#include "core/mesh/surface_bake.h"
#include "core/runtime/tissue.h"
#include "core/scene/scene.h"
#include "tests/test_paths.h"

namespace bleedsim::test {

// Lays `scene` on the turbinate over `domain`; returns the surface maps, baked as the surface stage
// bakes them (SurfaceMap{maps.frame.data(), maps.gravity.data(), scene.domain.grid()} reads them).
inline SurfaceMaps lay_on_turbinate(Scene& scene, const Domain& domain) {
  scene.domain = domain;
  scene.tissue = procedural_tissue(domain.width_px, domain.height_px, 5);
  TissueMesh mesh = load_tissue_mesh(source_dir() + "/scenarios/meshes/turbinate.obj");
  SurfaceMaps maps = bake_surface_maps(mesh, texture_panel(scene.domain), device_gravity_mm_s2(scene));
  scene.mesh = std::make_shared<const MeshSurface>(std::move(mesh));
  return maps;
}

}  // namespace bleedsim::test
