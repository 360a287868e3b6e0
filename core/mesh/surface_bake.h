#pragma once
// The surface maps of a tissue mesh (core/physics/surface.h has what they mean; docs/mesh.md): for
// every texel of the panel, its triangle's map from panel to surface millimetres in the frame of
// the tangent plane, the tangential gravity in that frame, and whether any triangle covers it.
// Baked once per run on the host, in double, then rounded to the floats both backends read.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/tissue_mesh.h"

namespace bleedsim {

// The texture as the panel: pixels, and the millimetres texture coordinates are scaled by
// (panel x = u · width_mm, panel y = v · height_mm).
struct TexturePanel {
  int width_px = 0;
  int height_px = 0;
  double width_mm = 0.0;
  double height_mm = 0.0;
};

struct SurfaceMaps {
  int width = 0;
  int height = 0;
  std::vector<float> frame;    // width × height × kSurfaceFrameChannels: a, b, c, on the surface (1 or 0)
  std::vector<float> gravity;  // width × height × kSurfaceGravityChannels, mm/s²
  std::size_t covered = 0;     // texels on the surface
};

// Texel (i, j) belongs to the triangle whose uv footprint holds its centre ((i + ½)/W, (j + ½)/H),
// the lowest-numbered one where several do (a centre on a shared edge, or a uv map that overlaps
// itself). Texels no triangle covers take the frame and gravity of the nearest covered one (by
// rings of the 4-neighbourhood, ties to the first in row order) and are marked off the surface.
// `gravity_mm_s2` is in the mesh's frame. Throws std::invalid_argument when no texel is covered.
SurfaceMaps bake_surface_maps(const TissueMesh& mesh, const TexturePanel& panel, const Eigen::Vector3d& gravity_mm_s2);

// How much a triangle's map from panel to surface millimetres stretches: J's least and greatest
// singular values over the mesh (1 and 1 for the flat panel at its own size). The collision grid's
// cells are made large enough in panel mm for the least.
struct PanelStretch {
  double least = 1.0;
  double greatest = 1.0;
};
PanelStretch panel_stretch(const TissueMesh& mesh, const TexturePanel& panel);

// Whether some triangle's uvs hold a texel's centre: a mesh that covers none has no surface to bake.
bool covers_a_texel(const TissueMesh& mesh, const TexturePanel& panel);

// The most a mesh's least stretch may be: a panel mm at least this many mm of the surface everywhere
// is a texture whose uvs span too little of it for the mesh's size. The particles' collision grid
// and the spread's tiles are sized in panel mm by the least stretch, and past this their counts
// outgrow what they are counted in; a scene refuses such a mesh at tissue.mesh (docs/mesh.md).
constexpr double kMaxLeastStretch = 1e3;

}  // namespace bleedsim
