// Tissue meshes from OBJ files (core/io/mesh_obj.h): a parametric patch read back exactly, its
// area the faceted surface's closed form; and every kind of bad mesh refused naming the file, the
// face where there is one, and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/io/mesh_obj.h"
#include "core/runtime/input_error.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

fs::path write_mesh(const std::string& name, const std::string& text) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(test::binary_dir()) / "test-scratch" / info->test_suite_name() / info->name();
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::ofstream(file) << text;
  return file;
}

// A piece of a cylinder of radius r (mm) over `span` radians and height h, n facets around and m
// rows up, with uv = (θ / span, z / h) at its corners: the kind of curved sheet a turbinate is.
std::string cylinder_patch(double r, double span, double h, int n, int m) {
  std::ostringstream obj;
  obj.precision(17);
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) {
      const double theta = span * i / n;
      obj << "v " << r * std::cos(theta) << " " << r * std::sin(theta) << " " << h * j / m << "\n"
          << "vt " << double(i) / n << " " << double(j) / m << "\n";
    }
  const auto at = [&](int i, int j) { return std::to_string(j * (n + 1) + i + 1); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {  // a quad, which the reader fans into two triangles
      const std::string a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      obj << "f " << a << "/" << a << " " << b << "/" << b << " " << c << "/" << c << " " << d << "/" << d << "\n";
    }
  return obj.str();
}

// The message of the InputError loading `file` throws, or "" when it loads. A file that cannot be
// read at all (missing, too large) is refused as a file, without the key.
std::string refusal(const fs::path& file, const MeshBudget& budget = {}, const std::string& key = "tissue.mesh") {
  try {
    load_tissue_mesh(file.string(), budget);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, file.string());
    EXPECT_EQ(e.key(), key);
    return e.what();
  }
  return "";
}

TEST(TissueMesh, AParametricPatchReadsBackWithTheFacetedArea) {
  const double r = 6.0, span = 2.0, h = 20.0;
  const int n = 24, m = 10;
  const TissueMesh mesh = load_tissue_mesh(write_mesh("patch.obj", cylinder_patch(r, span, h, n, m)).string());
  ASSERT_EQ(mesh.positions.size(), std::size_t((n + 1) * (m + 1)));
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  ASSERT_EQ(mesh.triangles.size(), std::size_t(2 * n * m));
  // Each facet is a flat rectangle, its chord 2r·sin(Δθ/2) wide and h tall: the faceted surface's
  // area is n · 2r·sin(span / 2n) · h, exactly, whatever the triangles; the written coordinates
  // carry 17 digits, so the sum of 480 triangles agrees to ~1e-14 relative.
  const double faceted = n * 2.0 * r * std::sin(span / (2.0 * n)) * h;
  EXPECT_NEAR(mesh.area_mm2(), faceted, 1e-12 * faceted);
  // And it is within the facets' chord error of the smooth cylinder's r·span·h (1 − Δθ²/24 to first order).
  EXPECT_LT(std::fabs(mesh.area_mm2() / (r * span * h) - 1.0), std::pow(span / n, 2) / 24.0 * 1.01);
  // A corner keeps its uv: the last vertex is at θ = span, z = h, uv (1, 1).
  EXPECT_EQ(mesh.uvs.back(), Eigen::Vector2d(1.0, 1.0));
  EXPECT_NEAR(mesh.positions.back().z(), h, 1e-12);
}

TEST(TissueMesh, BadMeshesAreRefusedNamingTheFileAndTheProblem) {
  const std::string square_uv = "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n" + square_uv;
  struct Case {
    const char* name;
    std::string text;
    const char* gist;
  };
  const Case cases[] = {
      {"no-uv.obj", square + "f 1 2 3\n", "face 1 has no texture coordinate at its corner 1"},
      {"some-uv.obj", square + "f 1/1 2/2 3/3\nf 1/1 3/3 4\n", "face 2 has no texture coordinate at its corner 3"},
      {"flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\n" + square_uv + "f 1/1 2/2 3/3\n",
       "face 1 is degenerate: its corners lie on a line"},
      {"point.obj", square + "f 1/1 1/2 2/3\n", "face 1 is degenerate"},
      {"uv-line.obj", square + "vt 2 0\nf 1/1 2/2 3/5\n", "face 1 is degenerate in the texture"},
      {"junction.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n" + square_uv +
           "f 1/1 2/2 3/3\nf 2/2 1/1 4/4\nf 1/1 2/2 5/3\n",
       "the edge between vertices 1 and 2 borders 3 faces (face 1, face 2, face 3): the mesh is not a surface"},
      {"empty.obj", square, "the mesh has no faces"},
      {"past-v.obj", square + "f 1/1 2/2 99/3\n", "face 1 refers to vertex 99, not one of the file's 4"},
      {"past-vt.obj", square + "f 1/1 2/2 3/99\n", "face 1 refers to texture coordinate 99, not one of the file's 4"},
      {"vertex-0.obj", square + "f 1/1 2/2 0/3\n", "not a readable OBJ mesh: Failed parse `f' line(e.g. zero value for "
                                                 "face index. line 9.)"},
      {"infinite.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\n" + square_uv + "f 1/1 2/2 3/3\n",
       "vertex 2 is not a finite point"},
      {"nul.obj", square + std::string("f 1/1 2/2 3/3\0\n", 15), "holds a NUL byte"},
      // Line numbers are the file's, lines ending in \r\n or \r too, other statements blanked.
      {"crlf.obj", "g tissue\r\nusemtl mucosa\rv 0 0 0\r\n" + square + "f 1/1 2/2 0/3\r\n",
       "zero value for face index. line 12."},
  };
  for (const Case& c : cases) {
    const std::string said = refusal(write_mesh(c.name, c.text));
    EXPECT_NE(said.find(c.gist), std::string::npos) << c.name << ": " << said;
    EXPECT_NE(said.find(c.name), std::string::npos) << c.name << ": " << said;
  }
  // A missing file, and budgets: too many triangles, too many bytes (refused before it is read).
  const fs::path missing = write_mesh("here.obj", "").parent_path() / "missing.obj";
  EXPECT_NE(refusal(missing, {}, "").find("cannot read mesh file"), std::string::npos);
  const fs::path patch = write_mesh("patch.obj", cylinder_patch(5.0, 1.0, 5.0, 10, 10));
  EXPECT_NE(refusal(patch, MeshBudget{199, std::size_t(1) << 30})
                .find("the mesh has 200 triangles, more than the 199 a mesh may have"),
            std::string::npos);
  EXPECT_NE(refusal(patch, MeshBudget{1000, 100}, "").find("100"), std::string::npos);
  EXPECT_EQ(refusal(patch, MeshBudget{200, std::size_t(1) << 30}), "");
}

// What a tissue mesh does not need is not read: groups, materials, smoothing, tinyobjloader's
// skin weights (whose parsing is undefined on some inputs: the mesh fuzzer's find).
TEST(TissueMesh, StatementsBesidesGeometryAreIgnored) {
  const std::string text = "mtllib none.mtl\no sheet\ng tissue\ns 1\nusemtl mucosa\nvw 0 4e23 0.5\n"
                           "v 0 0 0\r\nv 2 0 0\rv 0 3 0\nvt 0 0\nvt 1 0\nvt 0 1\nl 1 2\nf 1/1 2/2 3/3\n";
  const TissueMesh mesh = load_tissue_mesh(write_mesh("extras.obj", text).string());
  EXPECT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.area_mm2(), 3.0);
}

// The shipped examples: the flat panel (its area the default scene's 32 × 24 mm), and the turbinate
// (scenarios/meshes/turbinate.obj, written by scripts/make-turbinate): 64 × 24 quads as triangles,
// its uv the unit square.
TEST(TissueMesh, TheShippedFlatPanelIsTheDefaultScenesPanel) {
  const TissueMesh mesh = load_tissue_mesh(test::source_dir() + "/scenarios/meshes/flat-panel.obj");
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.area_mm2(), 32.0 * 24.0);
}

TEST(TissueMesh, TheShippedTurbinateIsATissueMesh) {
  const TissueMesh mesh = load_tissue_mesh(test::source_dir() + "/scenarios/meshes/turbinate.obj");
  EXPECT_EQ(mesh.triangles.size(), 2u * 64u * 24u);
  Eigen::Vector2d low = mesh.uvs.front(), high = low;
  for (const Eigen::Vector2d& uv : mesh.uvs) low = low.cwiseMin(uv), high = high.cwiseMax(uv);
  EXPECT_EQ(low, Eigen::Vector2d(0.0, 0.0));
  EXPECT_EQ(high, Eigen::Vector2d(1.0, 1.0));
}

}  // namespace
}  // namespace bleedsim
