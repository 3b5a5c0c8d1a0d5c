// Mesh reading, writing and validation: round trips through every format, and each
// validation error with the element it must name.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::FlatGridSoup;
using testing::ObjText;
using testing::TempDir;
using testing::WriteFile;

PolygonSoup CurvedGrid() {
  // Non-round coordinates check that no precision is lost on the way.
  return testing::GridSoup(4, [](double x, double y) { return 0.1234567891234 * x * y + std::sqrt(2.0); });
}

void ExpectSameSoupGeometry(const PolygonSoup& a, const TriMesh& b, double tolerance) {
  ASSERT_EQ(a.points.size(), b.n_vertices());
  ASSERT_EQ(a.faces.size(), b.n_faces());
  for (size_t v = 0; v < a.points.size(); ++v)
    EXPECT_NEAR((a.points[v] - ToEigen(b.point(VertexHandle(static_cast<int>(v))))).norm(), 0.0, tolerance) << v;
  for (const auto f : b.faces()) {
    std::vector<int> ids;
    for (const auto v : b.fv_range(f)) ids.push_back(v.idx());
    const auto& expected = a.faces[f.idx()];
    // Same cyclic order (orientation kept).
    const auto start = std::find(ids.begin(), ids.end(), expected[0]) - ids.begin();
    ASSERT_LT(start, 3);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(ids[(start + k) % 3], expected[k]);
  }
}

TEST(MeshIo, ObjRoundTripKeepsDoublePrecision) {
  const auto dir = TempDir();
  const PolygonSoup soup = CurvedGrid();
  const TriMesh mesh = testing::ToMesh(soup);
  ASSERT_TRUE(WriteMesh(mesh, dir + "/m.obj").ok());
  TriMesh back;
  ASSERT_TRUE(ReadSurfaceMesh(dir + "/m.obj", &back).ok());
  ExpectSameSoupGeometry(soup, back, 1e-10);
}

TEST(MeshIo, PlyRoundTrip) {
  const auto dir = TempDir();
  const PolygonSoup soup = CurvedGrid();
  ASSERT_TRUE(WriteMesh(testing::ToMesh(soup), dir + "/m.ply").ok());
  TriMesh back;
  const Status s = ReadSurfaceMesh(dir + "/m.ply", &back);
  ASSERT_TRUE(s.ok()) << s.message();
  ExpectSameSoupGeometry(soup, back, 1e-6);
}

TEST(MeshIo, ReadsOffAndStl) {
  const auto dir = TempDir();
  const std::string off = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  TriMesh mesh;
  ASSERT_TRUE(ReadSurfaceMesh(WriteFile(dir, "m.off", off), &mesh).ok());
  EXPECT_EQ(mesh.n_vertices(), 4u);
  EXPECT_EQ(mesh.n_faces(), 2u);
  EXPECT_DOUBLE_EQ(mesh.point(VertexHandle(2))[2], 0.5);
  // ASCII STL repeats shared vertices per facet; the reader merges them.
  const std::string stl =
      "solid s\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\n"
      "endsolid s\n";
  ASSERT_TRUE(ReadSurfaceMesh(WriteFile(dir, "m.stl", stl), &mesh).ok());
  EXPECT_EQ(mesh.n_vertices(), 4u);
  EXPECT_EQ(mesh.n_faces(), 2u);
}

TEST(MeshIo, WritesPolygonMeshes) {
  const auto dir = TempDir();
  PolyMesh quad;
  std::vector<VertexHandle> v;
  for (auto p : {OpenMesh::Vec3d(0, 0, 0), OpenMesh::Vec3d(1, 0, 0), OpenMesh::Vec3d(1, 1, 0), OpenMesh::Vec3d(0, 1, 0)})
    v.push_back(quad.add_vertex(p));
  quad.add_face(v);
  ASSERT_TRUE(WriteMesh(quad, dir + "/q.obj").ok());
  PolygonSoup soup;
  ASSERT_TRUE(ReadPolygonSoup(dir + "/q.obj", &soup).ok());
  ASSERT_EQ(soup.faces.size(), 1u);
  EXPECT_EQ(soup.faces[0], (std::vector<int>{0, 1, 2, 3}));
}

TEST(MeshIo, MissingFileAndUnknownFormatNameTheFile) {
  const auto dir = TempDir();
  TriMesh mesh;
  Status s = ReadSurfaceMesh(dir + "/nope.obj", &mesh);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_NE(s.message().find("nope.obj: file not found"), std::string::npos) << s.message();
  s = ReadSurfaceMesh(WriteFile(dir, "m.3ds", "x"), &mesh);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_NE(s.message().find("unsupported mesh format '.3ds'"), std::string::npos) << s.message();
}

// Each validation failure: the soup, and text the message must contain.
struct BrokenCase {
  std::string name;
  PolygonSoup soup;
  std::string expected;
};

std::vector<BrokenCase> BrokenCases() {
  std::vector<BrokenCase> cases;
  cases.push_back({"empty", PolygonSoup{}, "the mesh is empty"});
  {
    PolygonSoup s = FlatGridSoup(2);
    s.points[4].y() = NAN;
    cases.push_back({"nonfinite", s, "vertex 4 has a non-finite coordinate"});
  }
  {
    // Face 0 is (0, 1, 4); moving vertex 4 to (0.5, 0, 0) puts it on the edge (0, 1).
    PolygonSoup s = FlatGridSoup(2);
    s.points[4] = Eigen::Vector3d(0.5, 0.0, 0.0);
    cases.push_back({"degenerate", s, "face 0 is degenerate (zero area)"});
  }
  {
    PolygonSoup s = FlatGridSoup(2);
    s.faces.push_back(s.faces[3]);
    cases.push_back({"duplicate", s, "faces 3 and 8 are duplicates"});
  }
  {
    PolygonSoup s = FlatGridSoup(2);  // a third face on edge (0, 4): the grid's diagonal
    s.points.emplace_back(0.5, 0.5, 1.0);
    s.faces.push_back({0, 4, 9});
    cases.push_back({"nonmanifold_edge", s, "non-manifold edge (0, 4) is shared by 3 faces"});
  }
  {
    PolygonSoup s = FlatGridSoup(2);
    std::swap(s.faces[5][1], s.faces[5][2]);
    cases.push_back({"orientation", s, "opposite orientations"});
  }
  {
    // Two triangles touching only at vertex 0: a bow tie.
    PolygonSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
    s.faces = {{0, 1, 2}, {0, 3, 4}};
    cases.push_back({"nonmanifold_vertex", s, "non-manifold vertex 0"});
  }
  {
    // A tetrahedron is closed.
    PolygonSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    s.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    cases.push_back({"closed", s, "no boundary"});
  }
  {
    PolygonSoup s = FlatGridSoup(1);
    s.faces = {{0, 1, 3, 2}};
    cases.push_back({"quad", s, "face 0 has 4 vertices"});
  }
  return cases;
}

TEST(MeshValidation, ValidGridPasses) {
  EXPECT_TRUE(ValidateSurfaceSoup(FlatGridSoup(3)).ok());
}

TEST(MeshValidation, EachProblemIsNamedWithItsElement) {
  for (const auto& c : BrokenCases()) {
    const Status s = ValidateSurfaceSoup(c.soup);
    EXPECT_EQ(s.code(), StatusCode::kInvalidInput) << c.name;
    EXPECT_NE(s.message().find(c.expected), std::string::npos) << c.name << ": " << s.message();
  }
}

TEST(MeshValidation, FileErrorsArePrefixedWithThePath) {
  const auto dir = TempDir();
  for (const auto& c : BrokenCases()) {
    if (c.name == "empty") continue;  // an empty OBJ is refused by the reader itself
    const std::string path = WriteFile(dir, c.name + ".obj", ObjText(c.soup));
    TriMesh mesh;
    const Status s = ReadSurfaceMesh(path, &mesh);
    EXPECT_EQ(s.code(), StatusCode::kInvalidInput) << c.name;
    EXPECT_EQ(s.message().rfind(path + ": ", 0), 0u) << s.message();
    EXPECT_NE(s.message().find(c.expected), std::string::npos) << c.name << ": " << s.message();
  }
}

TEST(MeshValidation, BrokenObjLinesAreNamed) {
  const auto dir = TempDir();
  TriMesh mesh;
  Status s = ReadSurfaceMesh(WriteFile(dir, "garbage.obj", "this is not a mesh\n"), &mesh);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_NE(s.message().find("garbage.obj: no vertices or faces found"), std::string::npos) << s.message();
  s = ReadSurfaceMesh(WriteFile(dir, "bad_v.obj", "v 0 0 0\nv 1 zero 0\n"), &mesh);
  EXPECT_NE(s.message().find("bad_v.obj:2: 'zero' is not a number"), std::string::npos) << s.message();
  s = ReadSurfaceMesh(WriteFile(dir, "bad_f.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"), &mesh);
  EXPECT_NE(s.message().find("bad_f.obj:4: 'x' is not a vertex index"), std::string::npos) << s.message();
  s = ReadSurfaceMesh(WriteFile(dir, "bad_i.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"), &mesh);
  EXPECT_NE(s.message().find("bad_i.obj: face 0 references missing vertex 6"), std::string::npos) << s.message();
}

TEST(MeshIo, ObjCornersWithTextureAndNormalIndicesAndNegativeIndices) {
  const auto dir = TempDir();
  const std::string obj = "# roof\no roof\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                          "f 1//1 2//1 3//1\nf -4/1/1 -2/1/1 -1/1/1\n";
  TriMesh mesh;
  const Status s = ReadSurfaceMesh(WriteFile(dir, "m.obj", obj), &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(mesh.n_faces(), 2u);
  EXPECT_EQ(mesh.n_vertices(), 4u);
}

}  // namespace
}  // namespace pqlayout
