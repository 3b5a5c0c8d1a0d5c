// A surface exported in georeferenced coordinates (UTM: hundreds of kilometres east, thousands
// north) is solved in a local frame and written back in the file's coordinates
// (pipeline/stage_surface.cc). Solved where it lay, the planarisation's face planes
// n·x = d were ill-conditioned: the Great Court dome at (500000, 5000000) planarised with
// vertices moved 16 m and came out 44 % softer; this 14 m dome moved them 2.0 m (0.71 m
// where it was exported near the origin).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

#include "geometry/mesh_io.h"
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

}  // namespace
}  // namespace pqlayout
