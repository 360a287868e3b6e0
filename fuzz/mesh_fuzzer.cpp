// The tissue mesh reader (core/io/mesh_obj.h: tinyobjloader, then the checks) on any bytes: it
// must refuse them with an InputError or give a mesh whose every index is in range, never crash,
// read out of bounds or hold more triangles than its budget.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/io/mesh_obj.h"
#include "core/runtime/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  bleedsim::MeshBudget budget;
  budget.triangles = 1u << 16;
  try {
    const bleedsim::TissueMesh mesh = bleedsim::parse_tissue_mesh(text, "fuzzed.obj", budget);
    if (mesh.triangles.empty() || mesh.triangles.size() > budget.triangles) std::abort();
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k)
        if (t.corner[k] < 0 || std::size_t(t.corner[k]) >= mesh.positions.size() || t.uv[k] < 0 ||
            std::size_t(t.uv[k]) >= mesh.uvs.size())
          std::abort();
  } catch (const bleedsim::InputError&) {
  }
  return 0;
}
