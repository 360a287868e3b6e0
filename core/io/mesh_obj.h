#pragma once
// A tissue mesh (core/mesh/tissue_mesh.h) from a Wavefront OBJ file (docs/mesh.md): its text checked
// as written (every number a finite decimal within bounds, every index naming an element the file
// has), read with Debian's tinyobjloader, its polygons cut into triangles by ear clipping, then
// checked for what the bleeding on it needs: a uv at every corner, no triangle without area in space
// or in the texture, every edge shared by at most two triangles (a surface, not a junction of
// sheets), and no more triangles than a budget allows. Anything else is an InputError naming the
// file, the line, the face where there is one, and the problem.
#include <cstddef>
#include <optional>
#include <string>

#include "core/mesh/tissue_mesh.h"
#include "core/runtime/memory.h"

namespace bleedsim {

// The most triangles a mesh may have, and the most bytes its file may have (read before parsing, so
// that a huge file is refused before it is read into memory).
struct MeshBudget {
  std::size_t triangles = 1u << 22;
  std::size_t file_bytes = std::size_t(512) << 20;
  // The host memory reading the file may take (none given: what available_host_memory() reports).
  std::optional<std::size_t> memory_room = {};
};

// The most host memory load_tissue_mesh() holds at once for `path`, under `key`: counted from a pass
// over the file, a buffer at a time, that counts its elements, its faces and their corners.
MemoryPart mesh_memory(const std::string& path, const std::string& key);

// Reads and checks `path` (see above); throws InputError naming the file and, where it can, the line
// and the face (1-based, in file order, after polygons are cut into triangles), under the key `key`.
// Its memory (mesh_memory()) is counted, and refused past the budget's room, before it is read.
TissueMesh load_tissue_mesh(const std::string& path, const MeshBudget& budget = {},
                            const std::string& key = "tissue.mesh");
// The same for the text of an OBJ file, `path` naming it in messages. A material library it names
// is not read.
TissueMesh parse_tissue_mesh(const std::string& text, const std::string& path, const MeshBudget& budget = {},
                             const std::string& key = "tissue.mesh");

}  // namespace bleedsim
