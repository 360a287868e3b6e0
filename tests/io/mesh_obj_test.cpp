// Tissue meshes from OBJ files (core/io/mesh_obj.h): a parametric patch read back exactly, its
// area the faceted surface's closed form; and every kind of bad mesh refused naming the file, the
// face where there is one, and the problem.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

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
      {"past-v.obj", square + "f 1/1 2/2 99/3\n", "past-v.obj:9: tissue.mesh: corner 3 names vertex 99, and the file has 4"},
      {"past-vt.obj", square + "f 1/1 2/2 3/99\n", "corner 3 names texture coordinate 99, and the file has 4"},
      {"vertex-0.obj", square + "f 1/1 2/2 0/3\n", "corner 3 names vertex 0: they count from 1"},
      {"infinite.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\n" + square_uv + "f 1/1 2/2 3/3\n",
       "infinite.obj:2: tissue.mesh: vertex 2's x is '1e999', out of a double's range"},
      {"nul.obj", square + std::string("f 1/1 2/2 3/3\0\n", 15), "holds a NUL byte"},
      // Line numbers are the file's, lines ending in \r\n or \r too, other statements blanked.
      {"crlf.obj", "g tissue\r\nusemtl mucosa\rv 0 0 0\r\n" + square + "f 1/1 2/2 0/3\r\n",
       "crlf.obj:12: tissue.mesh: corner 3 names vertex 0"},
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

// Issue 38, items 8 and 15: tinyobjloader read a number that is not one as 0 ("nan", "inf", "abc",
// "0x10") or as its start ("5abc" as 5), and the mesh was taken; a NaN that made three corners
// collinear was then called degenerate. Every number of a v, vt or vn line must be a whole, finite
// decimal number of at most 1e6, and a line that has another is refused at its line, by what it is.
TEST(TissueMesh, ANumberThatIsNotAFiniteDecimalIsRefusedAtItsLine) {
  const std::string uvs = "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";  // lines 5-8 after four v lines
  const std::string faces = "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  const auto with_z = [&](const std::string& z) { return "v 0 0 0\nv 32 0 0\nv 32 -24 " + z + "\nv 0 -24 0\n" + uvs + faces; };
  struct Case {
    std::string text;
    const char* gist;
  };
  const Case cases[] = {
      {with_z("nan"), ":3: tissue.mesh: vertex 3's z is 'nan', not a finite number"},
      {with_z("-nan"), ":3: tissue.mesh: vertex 3's z is '-nan', not a finite number"},
      {with_z("inf"), ":3: tissue.mesh: vertex 3's z is 'inf', not a finite number"},
      {with_z("abc"), ":3: tissue.mesh: vertex 3's z is 'abc', not a decimal number"},
      {with_z("0x10"), ":3: tissue.mesh: vertex 3's z is '0x10', not a decimal number"},
      {with_z("5abc"), ":3: tissue.mesh: vertex 3's z is '5abc', not a decimal number"},
      {with_z("1e999"), ":3: tissue.mesh: vertex 3's z is '1e999', out of a double's range"},
      {with_z("-2e6"), ":3: tissue.mesh: vertex 3's z is '-2e6', beyond ±1e6, the largest a mesh's numbers may be"},
      {"v 0 0 0\nv 32 0 0\nv 32 -24\nv 0 -24 0\n" + uvs + faces,
       ":3: tissue.mesh: vertex 3 has 2 numbers; a v line has x y z (and may add w, or a colour r g b)"},
      {"v 0 0 0\nv 32 0 0\nv 32 -24 0\nv 0 -24 0\nvt 0 0\nvt 1 0.5x\nvt 1 1\nvt 0 1\n" + faces,
       ":6: tissue.mesh: texture coordinate 2's v is '0.5x', not a decimal number"},
      {"v 0 0 0\nv 32 0 0\nv 32 -24 0\nv 0 -24 0\nvt 0 0\nvt 1\nvt 1 1\nvt 0 1\n" + faces,
       ":6: tissue.mesh: texture coordinate 2 has 1 number; a vt line has u v (and may add w)"},
      {"v 0 0 0\nv 32 0 0\nv 32 -24 0\nv 0 -24 0\n" + uvs + "vn 0 0 nan\n" + faces,
       ":9: tissue.mesh: normal 1's z is 'nan', not a finite number"},
  };
  for (const Case& c : cases) {
    const std::string said = refusal(write_mesh("number.obj", c.text));
    EXPECT_NE(said.find("number.obj" + std::string(c.gist)), std::string::npos) << c.gist << "\n said: " << said;
  }
  // The NaN that tinyobjloader read as 0, putting the corners on a line, is named as what it is.
  const std::string line = refusal(write_mesh("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 nan\n" + uvs + "f 1/1 2/2 3/3\n"));
  EXPECT_NE(line.find("line.obj:3: tissue.mesh: vertex 3's z is 'nan', not a finite number"), std::string::npos) << line;
  EXPECT_EQ(line.find("degenerate"), std::string::npos) << line;
}

// Issue 38, item 9: tinyobjloader narrowed indices through atoi, so 4294967299 was vertex 3, and
// 99999999999 and -5 were reported as vertices 1215752191 and 0. An index is checked as written: a
// whole number naming a vertex the file has, counting from 1, or back from the line with -1 the
// latest (the OBJ spec's relative indices, which are read).
TEST(TissueMesh, AnIndexIsCheckedAsWrittenBeforeItIsNarrowed) {
  const std::string square = "v 0 0 0\nv 32 0 0\nv 32 -24 0\nv 0 -24 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  struct Case {
    std::string face;
    const char* gist;
  };
  const Case cases[] = {
      {"f 1/1 2/2 4294967299/3", ":9: tissue.mesh: corner 3 names vertex 4294967299, and the file has 4"},
      {"f 1/1 2/2 99999999999/3", ":9: tissue.mesh: corner 3 names vertex 99999999999, and the file has 4"},
      {"f 1/1 2/2 99999999999999999999999/3",
       ":9: tissue.mesh: corner 3 names vertex 99999999999999999999999, and the file has 4"},
      {"f 1/1 2/2 3/4294967297", ":9: tissue.mesh: corner 3 names texture coordinate 4294967297, and the file has 4"},
      {"f 1/1 2/2 -5/3", ":9: tissue.mesh: corner 3 names vertex -5, 5 back, and 4 come before it"},
      {"f 1/1 2/2 0/3", ":9: tissue.mesh: corner 3 names vertex 0: they count from 1 (or back from -1)"},
      {"f 1/1 2/2 3x/3", ":9: tissue.mesh: corner 3 names vertex '3x', not a whole number"},
      {"f 1/1 2/2 +3/3", ":9: tissue.mesh: corner 3 names vertex '+3', not a whole number"},
      {"f 1/1 2/2 3/3/1/1", ":9: tissue.mesh: corner 3 is '3/3/1/1', not v, v/vt, v//vn or v/vt/vn"},
      {"f 1/1 2/2 3/", ":9: tissue.mesh: corner 3 is '3/', not v, v/vt, v//vn or v/vt/vn"},
      {"f 1/1 2/2", ":9: tissue.mesh: a face has 2 corners; it needs 3 or more"},
  };
  for (const Case& c : cases) {
    const std::string said = refusal(write_mesh("index.obj", square + c.face + "\n"));
    EXPECT_NE(said.find("index.obj" + std::string(c.gist)), std::string::npos) << c.face << "\n said: " << said;
  }
  // Relative indices count back from their line: -1 is the latest vertex written before it. The
  // face after three vertices names 1, 2, 3; the one after the fourth, 2, 3, 4 (v 4 is at x 0).
  const TissueMesh mesh = load_tissue_mesh(
      write_mesh("relative.obj", "vt 0 0\nvt 1 0\nvt 1 1\nv 0 0 0\nv 32 0 0\nv 32 -24 0\nf -3/1 -2/2 -1/3\n"
                                 "v 0 -24 0\nf -3/1 -2/2 -1/3\n")
          .string());
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0].corner, (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1].corner, (std::array<int, 3>{1, 2, 3}));
  EXPECT_EQ(mesh.area_mm2(), 32.0 * 24.0);
}

// A polygon's corners as one face of an OBJ file, uv = its x and y over 100 mm, about the middle.
std::string polygon_obj(const std::vector<Eigen::Vector3d>& corners) {
  std::ostringstream obj;
  obj.precision(17);
  for (const Eigen::Vector3d& p : corners)
    obj << "v " << p.x() << " " << p.y() << " " << p.z() << "\nvt " << 0.5 + p.x() / 100 << " " << 0.5 + p.y() / 100 << "\n";
  obj << "f";
  for (std::size_t k = 1; k <= corners.size(); ++k) obj << " " << k << "/" << k;
  return obj.str() + "\n";
}

// Twice the signed area of a polygon in the plane z = const, by the shoelace formula.
double twice_shoelace_area(const std::vector<Eigen::Vector3d>& corners) {
  double sum = 0;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const Eigen::Vector3d& a = corners[k];
    const Eigen::Vector3d& b = corners[(k + 1) % corners.size()];
    sum += a.x() * b.y() - b.x() * a.y();
  }
  return sum;
}

// Issue 38, item 10: a 20-corner star was cut into 11 triangles of 1.8 times its area (tinyobjloader's
// own clipping, which depends on where the polygon lies), and a dart, a quad with a notch, along its
// shorter diagonal, which runs outside it. A face is cut by ear clipping into its corners − 2
// triangles, each turned as the polygon is (none folds over another), that add up to its area.
void expect_cut_into_its_own_area(const std::string& name, const std::vector<Eigen::Vector3d>& polygon, double area) {
  SCOPED_TRACE(name);
  // The closed form against the shoelace formula's area of the corners as written.
  EXPECT_NEAR(twice_shoelace_area(polygon) / 2, area, 1e-12 * area);
  const TissueMesh mesh = load_tissue_mesh(write_mesh(name, polygon_obj(polygon)).string());
  ASSERT_EQ(mesh.triangles.size(), polygon.size() - 2);
  double sum = 0;
  for (const TissueMesh::Triangle& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[t.corner[0]];
    const Eigen::Vector3d normal = (mesh.positions[t.corner[1]] - a).cross(mesh.positions[t.corner[2]] - a);
    EXPECT_GT(normal.z(), 0.0) << "a triangle turned against the polygon (it folds over another)";
    sum += normal.norm() / 2;
  }
  EXPECT_NEAR(sum, area, 1e-12 * area);
  EXPECT_NEAR(mesh.area_mm2(), area, 1e-12 * area);
}

TEST(TissueMesh, ANonConvexPolygonIsCutIntoTrianglesOfItsOwnArea) {
  // A star of 10 points, 6 mm out and 2.5 mm in: 2n triangles of ½ R r sin(π / n) about its middle.
  const int points = 10;
  const double outer = 6.0, inner = 2.5;
  const Eigen::Vector3d middle(30.0, -20.0, 7.0);
  std::vector<Eigen::Vector3d> star;
  for (int k = 0; k < 2 * points; ++k) {
    const double angle = M_PI * k / points, r = k % 2 ? inner : outer;
    star.push_back(middle + Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), 0.0));
  }
  expect_cut_into_its_own_area("star.obj", star, points * outer * inner * std::sin(M_PI / points));
  // A dart: the triangle (0,0), (4,0), (2,5) less the notch (0,0), (4,0), (2,0.5): 10 − 1 mm². Its
  // diagonal from corner 1 to 3 (4 mm) is shorter than from 2 to 4 (4.5 mm), and outside it.
  expect_cut_into_its_own_area("dart.obj", {{0, 0, 0}, {2, 0.5, 0}, {4, 0, 0}, {2, 5, 0}}, 9.0);
}

// A convex quad is split as tinyobjloader split it, along its shorter diagonal (on a tie, from its
// second corner to its fourth), its triangles written from their lowest corner: a mesh of quads
// keeps the triangles, and so the bytes, it had.
TEST(TissueMesh, AConvexQuadIsSplitAlongItsShorterDiagonalAsBefore) {
  using Corners = std::array<int, 3>;
  struct Case {
    std::vector<Eigen::Vector3d> quad;
    Corners first, second;
  };
  const Case cases[] = {
      // The diagonal from corner 1 to 3 is the shorter: (0,1,2) and (0,2,3).
      {{{0, 0, 0}, {4, -1, 0}, {5, 3, 0}, {-1, 4, 0}}, {0, 1, 2}, {0, 2, 3}},
      // From corner 2 to 4: (0,1,3) and (1,2,3).
      {{{0, 0, 0}, {4, 0, 0}, {9, 3, 0}, {0, 3, 0}}, {0, 1, 3}, {1, 2, 3}},
      // A square, its diagonals equal: from corner 2 to 4.
      {{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, {0, 1, 3}, {1, 2, 3}},
  };
  for (const Case& c : cases) {
    const Eigen::Vector3d d13 = c.quad[2] - c.quad[0], d24 = c.quad[3] - c.quad[1];
    ASSERT_EQ(d13.squaredNorm() < d24.squaredNorm(), (c.first == Corners{0, 1, 2}));
    const TissueMesh mesh = load_tissue_mesh(write_mesh("quad.obj", polygon_obj(c.quad)).string());
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.triangles[0].corner, c.first);
    EXPECT_EQ(mesh.triangles[1].corner, c.second);
  }
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
