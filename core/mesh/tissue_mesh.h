#pragma once
// A tissue mesh (docs/mesh.md): triangles in millimetres with a texture coordinate at every corner,
// the texture being where the bleeding lives. core/io/mesh_obj.h reads one from an OBJ file and
// checks it; this is what the simulation sees of it.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace bleedsim {

struct TissueMesh {
  struct Triangle {
    std::array<int, 3> corner;  // into positions
    std::array<int, 3> uv;      // into uvs
  };
  std::vector<Eigen::Vector3d> positions;  // mm
  std::vector<Eigen::Vector2d> uvs;        // the texture's coordinates, 0 … 1 across it
  std::vector<Triangle> triangles;

  // The surface's area, Σ ½ |(b − a) × (c − a)| (mm²).
  double area_mm2() const;
};

// Where a mesh sits in the device frame: its points scaled, turned about the device's x, then y,
// then z axis (R = R_z · R_y · R_x, angles in degrees), then moved by `position_mm`.
struct MeshPlacement {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();
  double scale = 1.0;
};

// The mesh as placed: every position p becomes position + scale · R · p (uvs unchanged). Exact for
// the identity rotation and a unit scale: a flat panel placed so lands on the same numbers.
TissueMesh placed(TissueMesh mesh, const MeshPlacement& placement);

}  // namespace bleedsim
