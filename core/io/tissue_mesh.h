#pragma once
// A tissue mesh from a Wavefront OBJ file (issue 16: the tissue in 3D): triangles with a texture
// coordinate at every corner, the texture being where the bleeding lives. Read with Debian's
// tinyobjloader (polygons fanned into triangles), then checked for what the bleeding on it needs:
// a uv at every corner, no triangle without area in space or in the texture, every edge shared by
// at most two triangles (a surface, not a junction of sheets), finite coordinates, and no more
// triangles than a budget allows. Anything else is an InputError naming the file, the face and the
// problem.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace bleedsim {

struct TissueMesh {
  struct Triangle {
    std::array<int, 3> corner;  // into positions
    std::array<int, 3> uv;      // into uvs
  };
  std::vector<Eigen::Vector3d> positions;  // in the file's units (mm)
  std::vector<Eigen::Vector2d> uvs;        // the texture's coordinates, 0 … 1 across it
  std::vector<Triangle> triangles;

  // The surface's area, Σ ½ |(b − a) × (c − a)| (mm²).
  double area_mm2() const;
};

// The most triangles a mesh may have, and the most bytes its file may have (read before parsing, so
// that a huge file is refused before it is read into memory).
struct MeshBudget {
  std::size_t triangles = 1u << 22;
  std::size_t file_bytes = std::size_t(512) << 20;
};

// Reads and checks `path` (see above); throws InputError naming the file and, where it can, the face
// (1-based, in file order, after polygons are fanned into triangles) and the key `key`.
TissueMesh load_tissue_mesh(const std::string& path, const MeshBudget& budget = {},
                            const std::string& key = "tissue.mesh");
// The same for the text of an OBJ file, `path` naming it in messages. A material library it names
// is not read.
TissueMesh parse_tissue_mesh(const std::string& text, const std::string& path, const MeshBudget& budget = {},
                             const std::string& key = "tissue.mesh");

}  // namespace bleedsim
