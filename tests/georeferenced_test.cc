// A surface exported in georeferenced coordinates (UTM: hundreds of kilometres east, thousands
// north) is solved in a local frame and written back in the file's coordinates
// (pipeline/stage_surface.cc). Solved where it lay, the planarisation's face planes
// n·x = d were ill-conditioned: the Great Court dome at (500000, 5000000) planarised with
// vertices moved 16 m and came out 44 % softer; this 14 m dome moved them 2.0 m (0.71 m
// where it was exported near the origin).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"
#include "tests/test_cli.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

TEST(Georeferenced, ARoofFarFromTheOriginIsSolvedInALocalFrameAndWrittenBack) {
  const Eigen::Vector3d offset(500000.0, 5000000.0, 100.0);
  const TriMesh dome = testing::GeneratedMesh("dome_circular", 14.0, 14.0, 2.5, 0.6);
  PolygonSoup soup;
  for (const auto v : dome.vertices()) soup.points.push_back(ToEigen(dome.point(v)) + offset);
  for (const auto f : dome.faces()) {
    soup.faces.emplace_back();
    for (const auto v : dome.fv_range(f)) soup.faces.back().push_back(v.idx());
  }
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome_utm.obj", testing::ObjText(soup));
  testing::WriteFile(dir, "c.yaml",
                     "surface:\n  file: dome_utm.obj\nlayout:\n  spacing: 1.5\n"
                     "boundary:\n  default: free\n  rules: [{select: {box: [499990, 4999990, 0, 500010, 5000010, 200]}, "
                     "condition: fixed}]\n");
  const testing::CliResult r = testing::RunPqlayout(dir, "run c.yaml --out result --until planarize");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("is georeferenced: solved in a local frame"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(testing::ReadFile(dir + "/result/report.json"));
  const auto& s = report["stages"]["surface"];
  // The bounding box's centre rounded: the rim at z = 100, the crown at 102.5.
  EXPECT_EQ(s["origin"], nlohmann::json::array({500000.0, 5000000.0, 101.0}));
  EXPECT_EQ(s["supports"]["fixed"].get<int>(), s["n_boundary_vertices"].get<int>());  // the box, in file coordinates
  EXPECT_NEAR(s["bbox_min"][0].get<double>(), 499993.0, 1e-6);
  const auto& p = report["stages"]["planarize"];
  EXPECT_LE(p["planarity_max"].get<double>(), 1e-3);
  EXPECT_LE(p["max_displacement"].get<double>(), 1.0) << "2.03 m solved in UTM coordinates";
  // The files are in the file's coordinates: every vertex of quads.obj within the dome's box.
  PolygonSoup quads;
  ASSERT_TRUE(ReadPolygonSoup(dir + "/result/quads.obj", &quads).ok());
  ASSERT_FALSE(quads.points.empty());
  for (const auto& q : quads.points) {
    EXPECT_LE((q - offset).head<2>().cwiseAbs().maxCoeff(), 7.0 + 1e-3) << q.transpose();
    EXPECT_NEAR(q.z(), offset.z() + 1.25, 1.3) << q.transpose();
  }
}

// The triangles of mesh, moved by offset, as a binary STL (float32 coordinates).
std::string BinaryStl(const TriMesh& mesh, const Eigen::Vector3d& offset) {
  std::string bytes(80, ' ');
  auto put32 = [&bytes](uint32_t v) {
    for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
  };
  auto put_float = [&put32](double value) {
    const float f = static_cast<float>(value);
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof(bits));
    put32(bits);
  };
  put32(static_cast<uint32_t>(mesh.n_faces()));
  for (const auto f : mesh.faces()) {
    for (int k = 0; k < 3; ++k) put_float(0.0);  // the normal, unused
    for (const auto v : mesh.fv_range(f))
      for (int k = 0; k < 3; ++k) put_float(mesh.point(v)[k] + offset[k]);
    bytes += std::string(2, '\0');
  }
  return bytes;
}

// A binary STL stores float32: 14-digit UTM coordinates keep 7, and the roof's shape is gone
// (at 5,000 km the coordinates are 0.5 m apart, nearly its 0.6 m edges). Refused in one line
// that says so, before the mesh is read as degenerate triangles or a different roof.
TEST(Georeferenced, Float32CoordinatesTooCoarseForTheTrianglesAreRefusedOrWarned) {
  const TriMesh dome = testing::GeneratedMesh("dome_circular", 14.0, 14.0, 2.5, 0.6);
  const auto dir = testing::TempDir();
  TriMesh mesh;
  testing::WriteFile(dir, "utm.stl", BinaryStl(dome, Eigen::Vector3d(500000.0, 5000000.0, 100.0)));
  const Status s = ReadSurfaceMesh(dir + "/utm.stl", &mesh);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_NE(s.message().find("m from the origin are 0.5 m apart, 107 % of the mean edge (0.469 m)"), std::string::npos)
      << s.message();
  EXPECT_NE(s.message().find("export it near the origin"), std::string::npos) << s.message();
  // 2 km away they are 0.12 mm apart, 0.02 % of an edge: read, with a warning; at the origin, silently.
  PolygonSoup soup;
  std::string warning;
  testing::WriteFile(dir, "km.stl", BinaryStl(dome, Eigen::Vector3d(2000.0, 2000.0, 0.0)));
  ASSERT_TRUE(ReadPolygonSoup(dir + "/km.stl", &soup).ok());
  ASSERT_TRUE(CheckCoordinatePrecision(soup, &warning).ok());
  EXPECT_NE(warning.find("float32 coordinates 2007 m from the origin are 0.000122 m apart, 0.028 % of"), std::string::npos) << warning;
  EXPECT_TRUE(ReadSurfaceMesh(dir + "/km.stl", &mesh).ok());
  testing::WriteFile(dir, "local.stl", BinaryStl(dome, Eigen::Vector3d::Zero()));
  ASSERT_TRUE(ReadPolygonSoup(dir + "/local.stl", &soup).ok());
  EXPECT_TRUE(soup.single_precision);
  warning.clear();
  ASSERT_TRUE(CheckCoordinatePrecision(soup, &warning).ok());
  EXPECT_EQ(warning, "");
}

}  // namespace
}  // namespace pqlayout
