#pragma once
// A polygon's triangles (docs/mesh.md, "Mesh files"): how a face of a mesh file with more than three
// corners becomes triangles, by ear clipping in the plane it faces. Each step cuts off the ear whose
// cut, the edge it leaves behind, is shortest (the first in the polygon's order on a tie): a convex
// quad is split along its shorter diagonal as tinyobjloader split it, and a polygon that is not
// convex into triangles that cover it once.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace bleedsim {

// The triangles of the polygon with these corners, in order: corners − 2 of them, as numbers into
// `corners`, each turned as the polygon turns and written from its lowest corner. None (an empty
// vector) when the polygon cannot be cut so: it crosses or touches itself, or it has no area.
std::vector<std::array<int, 3>> polygon_triangles(const std::vector<Eigen::Vector3d>& corners);

}  // namespace bleedsim
