// The tissue mesh reader (core/io/mesh_obj.h: tinyobjloader, then the checks) on any bytes: it
// must refuse them with an InputError or give a mesh whose every index is in range, never crash,
// read out of bounds or hold more triangles than its budget. Most mutations are made as OBJ
// statements (fuzz/obj_mutator.h), so that inputs reach past the reader's first checks; the rest
// are libFuzzer's own on the bytes, with the OBJ words of fuzz/mesh_fuzzer.dict.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "core/io/mesh_obj.h"
#include "core/runtime/input_error.h"
#include "fuzz/obj_mutator.h"

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

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

// Three mutations in four as OBJ statements; the fourth, and any that would outgrow libFuzzer's
// length limit, on the bytes: what no grammar foresees (a NUL, a lone \r, a cut number).
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned seed) {
  std::minstd_rand rng(seed);
  if (rng() % 4 != 0) {
    const std::string text = bleedsim::fuzz::mutate_obj(std::string(reinterpret_cast<const char*>(data), size), rng);
    if (text.size() <= max_size) {
      std::memcpy(data, text.data(), text.size());
      return text.size();
    }
  }
  return LLVMFuzzerMutate(data, size, max_size);
}
