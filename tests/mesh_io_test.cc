// Mesh reading, writing and validation: round trips through every format, and each
// validation error with the element it must name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"
#include "tests/run_helpers.h"
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

// surface.obj is written from a copy on the writer's thread (stage surface): the same bytes as
// the mesh's own writer, with a georeferenced origin added and a -0 coordinate kept.
TEST(MeshIo, ObjFromCopiedTrianglesIsTheSameBytes) {
  const auto dir = TempDir();
  PolygonSoup soup = CurvedGrid();
  soup.points[3].x() = -0.0;
  const TriMesh mesh = testing::ToMesh(soup);
  for (const Eigen::Vector3d& origin : {Eigen::Vector3d::Zero().eval(), Eigen::Vector3d(529000.25, 181000.5, 0.0)}) {
    ASSERT_TRUE(WriteMesh(mesh, dir + "/own.obj", origin).ok());
    const TriangleArrays copy = CopyTriangles(mesh);
    ASSERT_EQ(copy.triangles.size(), mesh.n_faces());
    ASSERT_TRUE(WriteObj(copy, dir + "/copy.obj", origin).ok());
    const std::string own = testing::ReadFile(dir + "/own.obj");
    EXPECT_GT(own.size(), 100u);
    EXPECT_EQ(testing::ReadFile(dir + "/copy.obj"), own);
  }
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

// A PLY file of the soup that also carries what readers must skip: a float and a uchar
// property between the coordinates, a per-face int, and an element of lists the reader does
// not know. format: ascii, binary_little_endian or binary_big_endian.
std::string PlyFile(const PolygonSoup& soup, const std::string& format) {
  std::ostringstream text;
  text.precision(17);
  text << "ply\nformat " << format << " 1.0\ncomment written by mesh_io_test\nelement vertex " << soup.points.size()
       << "\nproperty double x\nproperty float nx\nproperty double y\nproperty double z\nproperty uchar red\n"
       << "element face " << soup.faces.size() << "\nproperty list uchar int vertex_indices\nproperty int flags\n"
       << "element material 1\nproperty list ushort float ambient\nend_header\n";
  if (format == "ascii") {
    for (const auto& p : soup.points) text << p.x() << " 0.5 " << p.y() << " " << p.z() << " 255\n";
    for (const auto& f : soup.faces) text << f.size() << " " << f[0] << " " << f[1] << " " << f[2] << " 7\n";
    text << "2 0.25 0.75\n";
    return text.str();
  }
  std::string out = text.str();
  const bool big = format == "binary_big_endian";
  const auto put = [&](auto value) {  // the test machine is little-endian (x86-64)
    char bytes[sizeof(value)];
    std::memcpy(bytes, &value, sizeof(value));
    if (big) std::reverse(bytes, bytes + sizeof(value));
    out.append(bytes, sizeof(value));
  };
  for (const auto& p : soup.points) put(p.x()), put(0.5f), put(p.y()), put(p.z()), put(uint8_t{255});
  for (const auto& f : soup.faces) put(uint8_t{3}), put(f[0]), put(f[1]), put(f[2]), put(int32_t{7});
  put(uint16_t{2}), put(0.25f), put(0.75f);
  return out;
}

TEST(MeshIo, PlyAsciiAndBinaryOfBothByteOrdersAreReadExactly) {
  const auto dir = TempDir();
  const PolygonSoup soup = CurvedGrid();
  for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    PolygonSoup back;
    const Status s = ReadPolygonSoup(WriteFile(dir, format + ".ply", PlyFile(soup, format)), &back);
    ASSERT_TRUE(s.ok()) << format << ": " << s.message();
    ASSERT_EQ(back.points.size(), soup.points.size()) << format;
    for (size_t v = 0; v < soup.points.size(); ++v) EXPECT_EQ(back.points[v], soup.points[v]) << format << " " << v;
    EXPECT_EQ(back.faces, soup.faces) << format;
  }
}

TEST(MeshIo, ReadsOffVariantsAndBinaryStl) {
  const auto dir = TempDir();
  // Colours after each vertex and face, comments, counts on the keyword's line.
  const std::string coff = "COFF 4 2 0 # a coloured square\n# x y z r g b a\n0 0 0 1 0 0 1\n1 0 0 1 0 0 1\n"
                           "1 1 0.123456789012345 1 0 0 1\n\n0 1 0 1 0 0 1\n3 0 1 2 255 0 0\n3 0 2 3\n";
  PolygonSoup soup;
  ASSERT_TRUE(ReadPolygonSoup(WriteFile(dir, "m.off", coff), &soup).ok());
  ASSERT_EQ(soup.points.size(), 4u);
  EXPECT_EQ(soup.points[2].z(), 0.123456789012345);  // read as a double
  EXPECT_EQ(soup.faces, (std::vector<std::vector<int>>{{0, 1, 2}, {0, 2, 3}}));
  // Binary STL whose header starts with "solid", as many exporters write it: the size decides.
  std::string stl(80, ' ');
  stl.replace(0, 10, "solid roof");
  const auto put = [&stl](auto value) { stl.append(reinterpret_cast<const char*>(&value), sizeof(value)); };
  put(uint32_t{2});
  const float corners[2][9] = {{0, 0, 0, 1, 0, 0, 1, 1, 0.5f}, {0, 0, 0, 1, 1, 0.5f, 0, 1, 0}};
  for (const auto& triangle : corners) {
    for (float n : {0.f, 0.f, 1.f}) put(n);
    for (float c : triangle) put(c);
    put(uint16_t{0});
  }
  ASSERT_TRUE(ReadPolygonSoup(WriteFile(dir, "m.stl", stl), &soup).ok());
  ASSERT_EQ(soup.points.size(), 4u);  // the shared corners are merged
  EXPECT_EQ(soup.points[2], Eigen::Vector3d(1, 1, 0.5));
  EXPECT_EQ(soup.faces, (std::vector<std::vector<int>>{{0, 1, 2}, {0, 2, 3}}));
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
    if (c.name == "quad") continue;   // split when read (MeshIo.QuadsAreSplitAlongTheirShorterDiagonalWhenRead)
    if (c.name == "orientation") continue;  // turned over when read (SoupRepair.*)
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
  EXPECT_NE(s.message().find("bad_i.obj:4: vertex index 7 names no vertex (the file has 3)"), std::string::npos)
      << s.message();
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

// Files that crashed, hung or exhausted memory in OpenMesh's readers (issue 15), and the other
// ways a header can lie. Each is refused by ReadSurfaceMesh with one line that starts with the
// file's path; the readers end by construction (every count is checked against the file's
// size and every loop consumes input), so these run in microseconds.
struct HostileFile {
  std::string name, content, expected;
};

std::string LittleEndianU32(uint32_t value) { return std::string(reinterpret_cast<const char*>(&value), 4); }

// "element e0 0\nelement e1 0\n...": a header of n distinct, empty elements.
std::string ManyElements(int n) {
  std::string out;
  for (int k = 0; k < n; ++k) out += "element e" + std::to_string(k) + " 0\n";
  return out;
}

std::vector<HostileFile> HostileFiles() {
  const std::string ply_vertices = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string ply_ascii = "ply\nformat ascii 1.0\n" + ply_vertices;
  const std::string ply_face = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string points = "0 0 0\n1 0 0\n0 1 0\n";
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::string stl_header(80, ' ');
  return {
      // PLY: OpenMesh segfaulted on the first, looped forever printing on the second.
      {"property_first.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", ":3: 'property' before any 'element'"},
      {"no_end_header.ply", ply_ascii, ": the header has no 'end_header' line"},
      {"huge_count.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4294967295\nproperty float x\n"
                         "property float y\nproperty float z\nend_header\n" + std::string(12, '\0'),
       ":3: element 'vertex' declares 4294967295 items, more than the 12 bytes after the header can hold"},
      {"huge_list.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n" +
                        std::string(12, '\0') + LittleEndianU32(0xffffffffu) + std::string(8, '\0'),
       ": face 0: the file ends"},
      {"many_elements.ply", "ply\nformat ascii 1.0\n" + ManyElements(200000) + "end_header\n",
       ": the header declares no 'vertex' element"},  // took quadratic time to check for duplicate names
      {"negative_count.ply", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", ":3: expected 'element NAME COUNT'"},
      {"not.ply", "solid x\n", ": the first line is not 'ply'"},
      {"no_z.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
       ":3: element 'vertex': needs exactly one each of properties x, y and z"},
      {"float_index.ply", ply_ascii + "element face 1\nproperty list uchar float vertex_indices\nend_header\n",
       "vertex indices must be of an integer type, not float"},
      {"index.ply", ply_ascii + ply_face + points + "3 0 1 3\n", ":13: face 0: vertex index 3 names no vertex (the file has 3)"},
      {"negative_index.ply", ply_ascii + ply_face + points + "3 0 1 -1\n", ":13: face 0: vertex index -1 names no vertex"},
      {"word.ply", ply_ascii + ply_face + "0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n", ":11: vertex 1: 'abc' is not a number"},
      {"uchar.ply", ply_ascii + ply_face + points + "300 0 1 2\n", ":13: face 0: '300' is not a uchar"},
      {"short.ply", ply_ascii + ply_face + points + "3 0 1\n", ": face 0: the file ends"},
      {"inf.ply", ply_ascii + ply_face + "0 0 0\n1e999 0 0\n0 1 0\n3 0 1 2\n", ": vertex 1 has a non-finite coordinate"},
      // OFF: OpenMesh allocated without bound for these counts.
      {"negative.off", "OFF\n-5 -3 0\n", ":2: negative count (-5 vertices, -3 faces)"},
      {"huge.off", "OFF\n4294967295 1 0\n0 0 0\n", ":2: 4294967295 vertices and 1 faces cannot fit in the 25 bytes"},
      {"ends.off", "OFF\n3 1 0\n0.000 0.000 0.000\n1.000 0.000 0.000\n", ": the file ends after 2 of 3 vertices"},
      {"index.off", "OFF\n3 1 0\n" + points + "3 0 1 3\n", ":6: face 0: vertex index 3 names no vertex (the file has 3)"},
      {"corners.off", "OFF\n3 1 0\n" + points + "3 0 1\n", ":6: face 0: the face has 3 corners but lists 2 indices"},
      {"binary.off", "OFF BINARY\n", ":1: binary OFF is not read"},
      {"4d.off", "4OFF\n1 0 0\n0 0 0 1\n", ":1: '4OFF': only three-dimensional OFF is read"},
      {"keyword.off", "3 1 0\n" + points, ":1: expected the OFF keyword, not '3'"},
      {"inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e999 0\n3 0 1 2\n", ": vertex 2 has a non-finite coordinate"},
      // OBJ: 4294967299 used to wrap to 3 through the cast to int.
      {"wrap.obj", triangle + "f 1 2 4294967299\n", ":4: vertex index 4294967299 names no vertex"},
      {"wrap_negative.obj", triangle + "f 1 2 -4294967297\n", ":4: vertex index -4294967297 names no vertex"},
      {"overflow.obj", triangle + "f 1 2 99999999999999999999\n", ":4: '99999999999999999999' is not a vertex index"},
      {"inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n", ": vertex 1 has a non-finite coordinate"},
      // STL: neither kind, a count the size contradicts, and broken facets.
      {"short.stl", "abc", ": not an ASCII STL (it does not start with 'solid'), and the file is too short"},
      {"count.stl", stl_header + LittleEndianU32(0xffffffffu) + std::string(50, '\0'),
       "the header's 4294967295 triangles need 214748364834 bytes, the file has 134"},
      {"quad.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n",
       ":7: facet 0 has more than three vertices"},
      {"garbage.stl", "solid s\n\x01\x02 junk\n", ":2: unexpected '?\?' in an ASCII STL file"},
      {"open.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", ": the file ends inside facet 0"},
      {"nan.stl", stl_header + LittleEndianU32(1) + std::string(12, '\0') + std::string(4, '\xff') + std::string(34, '\0'),
       ": facet 0 has a non-finite coordinate"},
  };
}

TEST(MeshIo, HostileFilesAreRefusedWithOneLineNamingTheFile) {
  const auto dir = TempDir();
  for (const auto& c : HostileFiles()) {
    const std::string path = WriteFile(dir, c.name, c.content);
    TriMesh mesh;
    const Status s = ReadSurfaceMesh(path, &mesh);
    EXPECT_EQ(s.code(), StatusCode::kInvalidInput) << c.name;
    EXPECT_EQ(s.message().rfind(path + ":", 0), 0u) << s.message();
    EXPECT_NE(s.message().find(c.expected), std::string::npos) << c.name << ": " << s.message();
    EXPECT_EQ(s.message().find('\n'), std::string::npos) << s.message();
  }
}

}  // namespace
}  // namespace pqlayout

namespace pqlayout {
namespace {

// CAD render meshes are mostly quads: a quad is split along its shorter diagonal when read (a
// rhombus 4 m × 2 m across: the 2 m diagonal), a larger polygon is refused, naming what to do.
TEST(MeshIo, QuadsAreSplitAlongTheirShorterDiagonalWhenRead) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "quad.obj", "v -2 0 0\nv 0 -1 0\nv 2 0 0.1\nv 0 1 0\nf 1 2 3 4\n");
  TriMesh mesh;
  ASSERT_TRUE(ReadSurfaceMesh(dir + "/quad.obj", &mesh).ok());
  ASSERT_EQ(mesh.n_faces(), 2u);
  int interior = 0;
  for (const auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    ++interior;
    EXPECT_NEAR(mesh.calc_edge_length(e), 2.0, 1e-12);  // vertices 2 and 4 (1-based), not 1 and 3
  }
  EXPECT_EQ(interior, 1);
  for (const auto f : mesh.faces()) EXPECT_GT(mesh.normal(f)[2], 0.0);  // the quad's orientation kept

  testing::WriteFile(dir, "pentagon.obj", "v 0 0 0\nv 1 0 0\nv 1.3 1 0\nv 0.5 1.6 0\nv -0.3 1 0\nf 1 2 3 4 5\n");
  const Status s = ReadSurfaceMesh(dir + "/pentagon.obj", &mesh);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_NE(s.message().find("pentagon.obj: face 0 has 5 vertices: the reference surface must be a mesh of triangles "
                             "(quads are split when read; triangulate larger polygons)"),
            std::string::npos)
      << s.message();
  // A triangle written as a quad (its last vertex twice) is that triangle.
  testing::WriteFile(dir, "tri.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3 3\n");
  ASSERT_TRUE(ReadSurfaceMesh(dir + "/tri.obj", &mesh).ok());
  EXPECT_EQ(mesh.n_faces(), 1u);
  // A quad naming a vertex that does not exist is left to validation, which names it.
  testing::WriteFile(dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3 9\n");
  EXPECT_EQ(ReadSurfaceMesh(dir + "/bad.obj", &mesh).code(), StatusCode::kInvalidInput);
}

}  // namespace
}  // namespace pqlayout
