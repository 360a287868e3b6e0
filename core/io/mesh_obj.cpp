#include "core/io/mesh_obj.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <utility>

#include <Eigen/Geometry>

#include "core/io/text_file.h"
#include "core/runtime/input_error.h"

// Only this translation unit includes tinyobjloader; its reals are doubles here.
#define TINYOBJLOADER_IMPLEMENTATION
#define TINYOBJLOADER_USE_DOUBLE
#include <tiny_obj_loader.h>

namespace bleedsim {
namespace {

// A triangle this much smaller than the square of its longest edge has no area to speak of: its
// corners lie on a line (or on a point) to within rounding of coordinates of that size.
constexpr double kDegenerate = 1e-12;

double twice_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (b - a).cross(c - a).norm();
}

double twice_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - a, v = c - a;
  return std::fabs(u.x() * v.y() - u.y() * v.x());
}

template <class V>
bool degenerate(const V& a, const V& b, const V& c) {
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return !(twice_area(a, b, c) > kDegenerate * longest);
}

std::string face_name(std::size_t f) { return "face " + std::to_string(f + 1); }

// The OBJ statements a tissue mesh is made of: vertices, texture coordinates, normals and faces.
// Every other line is blanked (kept as a line, so that the reader's line numbers stay the file's):
// groups, materials and the like mean nothing here, and tinyobjloader's extensions are not all
// safe on any input (its `vw` weights convert an unchecked float to int: the mesh fuzzer's find).
// Lines end at \n, \r\n or a lone \r, as the reader's do.
struct Geometry {
  std::string text;          // the v, vt, vn and f lines; every other line left empty
  std::size_t triangles = 0; // what the f lines fan into: corners − 2 each
};

Geometry geometry_only(const std::string& text) {
  Geometry g;
  g.text.reserve(text.size());
  std::size_t start = 0;
  const auto blank = [&](std::size_t i) { return text[i] == ' ' || text[i] == '\t'; };
  while (start < text.size()) {
    std::size_t end = text.find_first_of("\r\n", start);
    if (end == std::string::npos) end = text.size();
    std::size_t word = start;
    while (word < end && blank(word)) ++word;
    std::size_t word_end = word;
    while (word_end < end && !blank(word_end)) ++word_end;
    const std::string keyword = text.substr(word, word_end - word);
    if (keyword == "v" || keyword == "vt" || keyword == "vn" || keyword == "f") g.text.append(text, start, end - start);
    if (keyword == "f") {
      std::size_t corners = 0;
      for (std::size_t i = word_end; i < end; ++i) corners += !blank(i) && blank(i - 1);
      if (corners >= 3) g.triangles += corners - 2;
    }
    g.text += '\n';
    start = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
  }
  return g;
}

}  // namespace

TissueMesh load_tissue_mesh(const std::string& path, const MeshBudget& budget, const std::string& key) {
  return parse_tissue_mesh(read_text_file(path, "mesh", budget.file_bytes), path, budget, key);
}

TissueMesh parse_tissue_mesh(const std::string& text, const std::string& path, const MeshBudget& budget,
                             const std::string& key) {
  const SourcePlace file{path, 0, 0};
  const auto fail = [&](const std::string& message) { throw InputError(file, key, message); };
  if (text.find('\0') != std::string::npos) fail("the mesh file holds a NUL byte: it is not an OBJ text file");
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;  // polygons as fans of triangles
  config.vertex_color = false;
  // The budget before tinyobjloader holds the faces in memory: a file's triangles are counted first.
  const Geometry geometry = geometry_only(text);
  if (geometry.triangles > budget.triangles)
    fail("the mesh has " + std::to_string(geometry.triangles) + " triangles, more than the " +
         std::to_string(budget.triangles) + " a mesh may have");
  tinyobj::ObjReader reader;
  // No material file: a tissue mesh's colour is its bleeding texture, and nothing else is read.
  if (!reader.ParseFromString(geometry.text, "", config)) {
    std::string why = reader.Error();
    while (!why.empty() && std::isspace(static_cast<unsigned char>(why.back()))) why.pop_back();
    fail("not a readable OBJ mesh: " + (why.empty() ? std::string("no reason given") : why));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();

  TissueMesh mesh;
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
    mesh.positions.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
  for (std::size_t i = 0; i + 1 < attrib.texcoords.size(); i += 2)
    mesh.uvs.emplace_back(attrib.texcoords[i], attrib.texcoords[i + 1]);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (!mesh.positions[v].allFinite()) fail("vertex " + std::to_string(v + 1) + " is not a finite point");
  for (std::size_t v = 0; v < mesh.uvs.size(); ++v)
    if (!mesh.uvs[v].allFinite()) fail("texture coordinate " + std::to_string(v + 1) + " (vt) is not finite");

  std::size_t faces = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) faces += shape.mesh.num_face_vertices.size();
  if (faces == 0) fail("the mesh has no faces (f lines)");

  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::string name = face_name(mesh.triangles.size());
      TissueMesh::Triangle t{};
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t& index = shape.mesh.indices[3 * f + k];
        if (index.texcoord_index < 0)
          fail(name + " has no texture coordinate at its corner " + std::to_string(k + 1) +
               ": a tissue mesh needs a uv (vt) at every corner, where its bleeding is drawn");
        if (index.vertex_index < 0 || std::size_t(index.vertex_index) >= mesh.positions.size())
          fail(name + " refers to vertex " + std::to_string(index.vertex_index + 1) + ", not one of the file's " +
               std::to_string(mesh.positions.size()));
        if (std::size_t(index.texcoord_index) >= mesh.uvs.size())
          fail(name + " refers to texture coordinate " + std::to_string(index.texcoord_index + 1) +
               ", not one of the file's " + std::to_string(mesh.uvs.size()));
        t.corner[k] = index.vertex_index;
        t.uv[k] = index.texcoord_index;
      }
      const auto& p = mesh.positions;
      const auto& q = mesh.uvs;
      if (degenerate(p[t.corner[0]], p[t.corner[1]], p[t.corner[2]]))
        fail(name + " is degenerate: its corners lie on a line, it has no area");
      if (degenerate(q[t.uv[0]], q[t.uv[1]], q[t.uv[2]]))
        fail(name + " is degenerate in the texture: its uvs lie on a line, it has no texels");
      mesh.triangles.push_back(t);
    }
  }

  // A surface: each edge (a pair of vertices) borders at most two triangles.
  std::map<std::pair<int, int>, std::vector<std::size_t>> edges;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& c = mesh.triangles[f].corner;
    for (int k = 0; k < 3; ++k) {
      const int a = c[k], b = c[(k + 1) % 3];
      std::vector<std::size_t>& sharing = edges[{std::min(a, b), std::max(a, b)}];
      sharing.push_back(f);
      if (sharing.size() > 2)
        fail("the edge between vertices " + std::to_string(std::min(a, b) + 1) + " and " +
             std::to_string(std::max(a, b) + 1) + " borders " + std::to_string(sharing.size()) + " faces (" +
             face_name(sharing[0]) + ", " + face_name(sharing[1]) + ", " + face_name(sharing[2]) +
             "): the mesh is not a surface (non-manifold)");
    }
  }
  return mesh;
}

}  // namespace bleedsim
