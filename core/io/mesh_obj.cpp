#include "core/io/mesh_obj.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <istream>
#include <map>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/io/text_file.h"
#include "core/mesh/polygon_triangles.h"
#include "core/runtime/count.h"
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

// The largest magnitude of a number in a mesh file: a kilometre, in millimetres, far past any tissue,
// and small enough that every area, stretch and texel range computed from the mesh is finite.
constexpr double kMaxMagnitude = 1e6;

// The most corners a face may have: tinyobjloader counts a face's corners in a byte, and ear
// clipping takes time as the square of a face's corners.
constexpr std::size_t kMaxCorners = 255;

// Refusals of the mesh file under the scenario's key: at one of its lines, or (line 0) as a whole.
struct Refusal {
  const std::string& path;
  const std::string& key;
  [[noreturn]] void at(std::size_t line, const std::string& message) const {
    throw InputError(SourcePlace{path, int(line), 0}, key, message);
  }
};

// A line of an OBJ file: its number (from 1), its text up to a comment ('#' to the line's end), and
// that text's keyword and the fields after it, split at blanks. Lines end at \n, \r\n or a lone \r,
// as the reader's do.
struct Statement {
  std::size_t line = 0;
  std::string_view text;
  std::string_view keyword;
  std::vector<std::string_view> fields;
};

template <class Visit>
void for_each_statement(std::string_view text, Visit&& visit) {
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  Statement s;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find_first_of("\r\n", start), text.size());
    ++s.line;
    s.text = text.substr(start, end - start);
    s.text = s.text.substr(0, s.text.find('#'));
    s.fields.clear();
    for (std::size_t i = 0; i < s.text.size();) {
      std::size_t j = i;
      while (j < s.text.size() && !blank(s.text[j])) ++j;
      if (j > i) s.fields.push_back(s.text.substr(i, j - i));
      i = j + 1;
    }
    s.keyword = s.fields.empty() ? std::string_view() : s.fields.front();
    if (!s.fields.empty()) s.fields.erase(s.fields.begin());
    visit(s);
    start = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
  }
}

// The elements a mesh file lists, in the order a face's corner names them (v/vt/vn): the keyword of
// their lines, their name in messages, their numbers' names and how many numbers a line may have.
struct ElementKind {
  std::string_view keyword;
  const char* name;
  std::array<const char*, 3> labels;
  std::vector<std::size_t> counts;
  const char* form;
};

const std::array<ElementKind, 3>& element_kinds() {
  static const std::array<ElementKind, 3> kinds{{
      {"v", "vertex", {"x", "y", "z"}, {3, 4, 6}, "a v line has x y z (and may add w, or a colour r g b)"},
      {"vt", "texture coordinate", {"u", "v", "w"}, {2, 3}, "a vt line has u v (and may add w)"},
      {"vn", "normal", {"x", "y", "z"}, {3}, "a vn line has x y z"},
  }};
  return kinds;
}

// What a mesh file holds, counted a buffer at a time as for_each_statement() would split it: its
// bytes, its v, vt and vn lines, its f lines, their corners and the triangles they are cut into.
struct MeshShape {
  std::uint64_t bytes = 0, faces = 0, corners = 0, triangles = 0;
  std::array<std::uint64_t, 3> elements{};
};

MeshShape shape_of(std::istream& in) {
  MeshShape shape;
  std::string keyword;  // the line's first field, up to a character longer than any element's
  std::uint64_t fields = 0;
  bool in_field = false, comment = false;
  const auto end_line = [&] {
    const std::uint64_t after = fields > 0 ? fields - 1 : 0;
    if (keyword == "f") {
      ++shape.faces;
      shape.corners += after;
      if (after >= 3) shape.triangles += after - 2;
    }
    for (std::size_t e = 0; e < shape.elements.size(); ++e)
      if (keyword == element_kinds()[e].keyword) ++shape.elements[e];
    keyword.clear();
    fields = 0;
    in_field = comment = false;
  };
  std::vector<char> buffer(1 << 16);
  while (in.read(buffer.data(), std::streamsize(buffer.size())) || in.gcount() > 0) {
    shape.bytes += std::uint64_t(in.gcount());
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      const char c = buffer[std::size_t(i)];
      if (c == '\n' || c == '\r') end_line();
      else if (c == '#') comment = true;
      else if (c == ' ' || c == '\t') in_field = false;
      else if (!comment) {
        if (!in_field) ++fields;
        in_field = true;
        if (fields == 1 && keyword.size() < 3) keyword += c;
      }
    }
  }
  end_line();
  return shape;
}

// The most reading holds at once, from what tinyobjloader and parse_tissue_mesh() keep of each
// element (their vectors counted at twice their size: they grow by doubling): tinyobjloader holds
// a v's x y z and weight, a vt's u v and w, a vn's x y z, a corner's three indices and a face's
// corner count, material and smoothing group; parse_tissue_mesh() a position and a uv, a face's
// line, a triangle's corners, uvs and line. Beside them, first, tinyobjloader's copy of the
// geometry text and its faces as it parses, each a vector of its corners; then the edge map, a node
// and a vector for each of about 1.5 edges a triangle.
MemoryPart memory_for(const MeshShape& shape, const std::string& path, const std::string& key) {
  const Count held = Count(2) * (Count(shape.elements[0]) * (32 + 24) + Count(shape.elements[1]) * (24 + 16) +
                                 Count(shape.elements[2]) * 24 + Count(shape.corners) * 12 + Count(shape.faces) * (9 + 8) +
                                 Count(shape.triangles) * (24 + 8));
  const Count text = Count(2) * shape.bytes;  // the file's text, and its geometry
  const Count parsing = shape.bytes + Count(shape.faces) * (64 + 32) + Count(shape.corners) * 12;
  const Count edges = Count(shape.triangles) * 180;
  return {key, "reading the mesh '" + path + "' (" + std::to_string(shape.triangles) + " triangles)",
          text + held + std::max(parsing, edges)};
}

// The OBJ statements a tissue mesh is made of: vertices, texture coordinates, normals and faces.
// Every other line is blanked (kept as a line, so that the reader's line numbers stay the file's):
// groups, materials and the like mean nothing here, and tinyobjloader's extensions are not all
// safe on any input (its `vw` weights convert an unchecked float to int: the mesh fuzzer's find).
struct Geometry {
  std::string text;                   // the v, vt, vn and f lines up to their comments; the rest empty
  std::size_t triangles = 0;          // what the f lines are cut into: corners − 2 each
  std::array<std::size_t, 3> elements{};  // the v, vt and vn lines
};

Geometry geometry_only(const std::string& text) {
  Geometry g;
  g.text.reserve(text.size());
  for_each_statement(text, [&](const Statement& s) {
    const auto& kinds = element_kinds();
    for (std::size_t e = 0; e < kinds.size(); ++e)
      if (s.keyword == kinds[e].keyword) {
        ++g.elements[e];
        g.text.append(s.text);
      }
    if (s.keyword == "f") {
      if (s.fields.size() >= 3) g.triangles += s.fields.size() - 2;
      g.text.append(s.text);
    }
    g.text += '\n';
  });
  return g;
}

// Why a number as written is not one a mesh may hold, or "": the whole field must be a decimal
// number as std::from_chars reads it, finite and at most kMaxMagnitude. (tinyobjloader reads
// "nan", "abc" and "0x10" as 0 and "5abc" as 5, so its values are taken only once the text passes.)
std::string number_problem(std::string_view written) {
  double value = 0;
  const char* end = written.data() + written.size();
  const auto [stop, error] = std::from_chars(written.data(), end, value);
  if (error == std::errc::invalid_argument || stop != end) return "not a decimal number";
  if (error == std::errc::result_out_of_range) return "out of a double's range";
  if (!std::isfinite(value)) return "not a finite number";
  if (std::fabs(value) > kMaxMagnitude) return "beyond ±1e6, the largest a mesh's numbers may be";
  return {};
}

// Why a corner's index as written names none of the `total` elements of its kind in the file,
// `before` of them above its line, or "": it must be a whole number from 1 up, or from −1 back
// (the OBJ spec's relative indices: −1 the latest above). Checked before tinyobjloader narrows it
// through atoi, which made 4294967299 vertex 3.
std::string index_problem(std::string_view written, const char* element, std::size_t total, std::size_t before) {
  const std::string names = std::string("names ") + element + " ";
  const std::string index_text(written);
  std::int64_t index = 0;
  const char* end = written.data() + written.size();
  const auto [stop, error] = std::from_chars(written.data(), end, index);
  if (error == std::errc::invalid_argument || stop != end) return names + "'" + index_text + "', not a whole number";
  if (error == std::errc() && index == 0) return names + index_text + ": they count from 1 (or back from -1)";
  if (written.front() != '-') {
    if (error == std::errc() && std::uint64_t(index) <= total) return {};
    return names + index_text + ", and the file has " + std::to_string(total);
  }
  if (error == std::errc() && index >= -std::int64_t(before)) return {};
  return names + index_text + ", " + index_text.substr(1) + " back, and " + std::to_string(before) +
         " come before it";
}

// A face's corner as written, v, v/vt, v//vn or v/vt/vn: its three indices, empty where left out;
// none when it is written otherwise.
std::optional<std::array<std::string_view, 3>> corner_indices(std::string_view corner) {
  std::array<std::string_view, 3> index{};
  std::size_t parts = 0;
  for (std::size_t start = 0;;) {
    if (parts == index.size()) return std::nullopt;
    const std::size_t slash = corner.find('/', start);
    index[parts++] = corner.substr(start, slash == std::string_view::npos ? slash : slash - start);
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  // Only v//vn leaves one out.
  if (index[0].empty() || (parts == 2 && index[1].empty()) || (parts == 3 && index[2].empty())) return std::nullopt;
  return index;
}

void check_numbers(const Statement& s, const ElementKind& kind, std::size_t number, const Refusal& refuse) {
  const std::string name = std::string(kind.name) + " " + std::to_string(number);
  for (std::size_t i = 0; i < s.fields.size(); ++i)
    if (const std::string problem = number_problem(s.fields[i]); !problem.empty())
      refuse.at(s.line, name + "'s " + (i < kind.labels.size() ? kind.labels[i] : "number " + std::to_string(i + 1)) +
                            " is '" + std::string(s.fields[i]) + "', " + problem);
  const std::size_t count = s.fields.size();
  if (std::find(kind.counts.begin(), kind.counts.end(), count) == kind.counts.end())
    refuse.at(s.line, name + " has " + std::to_string(count) + (count == 1 ? " number; " : " numbers; ") + kind.form);
}

void check_face(const Statement& s, const std::array<std::size_t, 3>& total, const std::array<std::size_t, 3>& before,
                const Refusal& refuse) {
  const std::size_t corners = s.fields.size();
  if (corners < 3)
    refuse.at(s.line, "a face has " + std::to_string(corners) + (corners == 1 ? " corner" : " corners") +
                          "; it needs 3 or more");
  if (corners > kMaxCorners)
    refuse.at(s.line, "a face has " + std::to_string(corners) + " corners, more than the " +
                          std::to_string(kMaxCorners) + " a face may have");
  for (std::size_t k = 0; k < corners; ++k) {
    const std::string corner = "corner " + std::to_string(k + 1);
    const std::optional<std::array<std::string_view, 3>> index = corner_indices(s.fields[k]);
    if (!index) refuse.at(s.line, corner + " is '" + std::string(s.fields[k]) + "', not v, v/vt, v//vn or v/vt/vn");
    for (std::size_t e = 0; e < index->size(); ++e)
      if (!(*index)[e].empty())
        if (const std::string problem = index_problem((*index)[e], element_kinds()[e].name, total[e], before[e]);
            !problem.empty())
          refuse.at(s.line, corner + " " + problem);
  }
}

// Checks every geometry statement as written (number_problem, index_problem, the corners a face
// has), and gives each face's line, in file order.
std::vector<std::size_t> checked_face_lines(const Geometry& geometry, const Refusal& refuse) {
  std::vector<std::size_t> face_lines;
  std::array<std::size_t, 3> seen{};
  for_each_statement(geometry.text, [&](const Statement& s) {
    const auto& kinds = element_kinds();
    for (std::size_t e = 0; e < kinds.size(); ++e)
      if (s.keyword == kinds[e].keyword) check_numbers(s, kinds[e], ++seen[e], refuse);
    if (s.keyword == "f") {
      check_face(s, geometry.elements, seen, refuse);
      face_lines.push_back(s.line);
    }
  });
  return face_lines;
}

// A face's triangles as corner numbers of the face: a triangle as it is, a polygon cut by ear
// clipping (core/mesh/polygon_triangles.h).
std::vector<std::array<int, 3>> face_triangles(const TissueMesh& mesh, const tinyobj::index_t* corners, std::size_t count,
                                               std::size_t line, const Refusal& refuse) {
  if (count == 3) return {{0, 1, 2}};
  std::vector<Eigen::Vector3d> polygon;
  for (std::size_t k = 0; k < count; ++k) polygon.push_back(mesh.positions[corners[k].vertex_index]);
  std::vector<std::array<int, 3>> triangles = polygon_triangles(polygon);
  if (triangles.empty())
    refuse.at(line, "the face's " + std::to_string(count) +
                        " corners cannot be cut into triangles: the polygon crosses or touches itself, or has no area");
  return triangles;
}

}  // namespace

MemoryPart mesh_memory(const std::string& path, const std::string& key) {
  std::ifstream in = open_text_file(path, "mesh");
  return memory_for(shape_of(in), path, key);
}

TissueMesh load_tissue_mesh(const std::string& path, const MeshBudget& budget, const std::string& key) {
  require_memory({mesh_memory(path, key)}, budget.memory_room.value_or(available_host_memory()), "host");
  return parse_tissue_mesh(read_text_file(path, "mesh", budget.file_bytes), path, budget, key);
}

TissueMesh parse_tissue_mesh(const std::string& text, const std::string& path, const MeshBudget& budget,
                             const std::string& key) {
  const Refusal refuse{path, key};
  if (text.find('\0') != std::string::npos) refuse.at(0, "the mesh file holds a NUL byte: it is not an OBJ text file");
  // The budget before tinyobjloader holds the faces in memory: a file's triangles are counted first.
  const Geometry geometry = geometry_only(text);
  if (geometry.triangles > budget.triangles)
    refuse.at(0, "the mesh has " + std::to_string(geometry.triangles) + " triangles, more than the " +
                     std::to_string(budget.triangles) + " a mesh may have");
  const std::vector<std::size_t> face_lines = checked_face_lines(geometry, refuse);
  if (face_lines.empty()) refuse.at(0, "the mesh has no faces (f lines)");
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // cut here, below
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // No material file: a tissue mesh's colour is its bleeding texture, and nothing else is read.
  if (!reader.ParseFromString(geometry.text, "", config)) {
    std::string why = reader.Error();
    while (!why.empty() && std::isspace(static_cast<unsigned char>(why.back()))) why.pop_back();
    refuse.at(0, "not a readable OBJ mesh: " + (why.empty() ? std::string("no reason given") : why));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();

  // Every number is finite and every index in range: the text was checked above.
  TissueMesh mesh;
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
    mesh.positions.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
  for (std::size_t i = 0; i + 1 < attrib.texcoords.size(); i += 2)
    mesh.uvs.emplace_back(attrib.texcoords[i], attrib.texcoords[i + 1]);

  std::vector<std::size_t> triangle_lines;  // the line of each triangle's face
  std::size_t face = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::index_t* corners = shape.mesh.indices.data();
    for (const unsigned char count : shape.mesh.num_face_vertices) {
      const std::size_t line = face_lines[face++];
      for (const std::array<int, 3>& triangle : face_triangles(mesh, corners, count, line, refuse)) {
        const std::string name = face_name(mesh.triangles.size());
        TissueMesh::Triangle t{};
        for (int k = 0; k < 3; ++k) {
          const tinyobj::index_t& index = corners[triangle[k]];
          if (index.texcoord_index < 0)
            refuse.at(line, name + " has no texture coordinate at its corner " + std::to_string(k + 1) +
                                ": a tissue mesh needs a uv (vt) at every corner, where its bleeding is drawn");
          t.corner[k] = index.vertex_index;
          t.uv[k] = index.texcoord_index;
        }
        const auto& p = mesh.positions;
        const auto& q = mesh.uvs;
        if (degenerate(p[t.corner[0]], p[t.corner[1]], p[t.corner[2]]))
          refuse.at(line, name + " is degenerate: its corners lie on a line, it has no area");
        if (degenerate(q[t.uv[0]], q[t.uv[1]], q[t.uv[2]]))
          refuse.at(line, name + " is degenerate in the texture: its uvs lie on a line, it has no texels");
        mesh.triangles.push_back(t);
        triangle_lines.push_back(line);
      }
      corners += count;
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
        refuse.at(triangle_lines[f],
                  "the edge between vertices " + std::to_string(std::min(a, b) + 1) + " and " +
                      std::to_string(std::max(a, b) + 1) + " borders " + std::to_string(sharing.size()) + " faces (" +
                      face_name(sharing[0]) + ", " + face_name(sharing[1]) + ", " + face_name(sharing[2]) +
                      "): the mesh is not a surface (non-manifold)");
    }
  }
  return mesh;
}

}  // namespace bleedsim
