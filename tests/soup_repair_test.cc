// The repairs a CAD export needs before validation (geometry/soup_repair.h): unwelded seams,
// T-junctions and orientation, each against the surface as it should have been exported, and
// the cases that must not be touched.
#include "geometry/soup_repair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include <nlohmann/json.hpp>

#include "geometry/mesh_validation.h"
#include "tests/test_cli.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

double Height(double x, double y) { return 0.05 * x * x - 0.03 * y + 0.02 * x * y; }

// A patch of the height field over [x0, x1] × [0, 6]: nx × ny cells, two triangles each.
// Its vertices are its own (the seam with a neighbouring patch is not shared).
void AddPatch(PolygonSoup* soup, double x0, double x1, int nx, int ny) {
  const int base = static_cast<int>(soup->points.size());
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = x0 + (x1 - x0) * i / nx, y = 6.0 * j / ny;
      soup->points.emplace_back(x, y, Height(x, y));
    }
  auto id = [&](int i, int j) { return base + j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      soup->faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup->faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

int BoundaryEdgeCount(const PolygonSoup& soup) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& f : soup.faces)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(f[k], f[(k + 1) % 3])];
  return static_cast<int>(std::count_if(uses.begin(), uses.end(), [](const auto& u) { return u.second == 1; }));
}

Eigen::Vector3d VectorArea(const PolygonSoup& soup) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (const auto& f : soup.faces)
    a += 0.5 * (soup.points[f[1]] - soup.points[f[0]]).cross(soup.points[f[2]] - soup.points[f[0]]);
  return a;
}

TEST(SoupRepair, AnUnweldedSeamIsWeldedExactlyOrWithinRounding) {
  for (const double gap : {0.0, 1e-7}) {
    PolygonSoup soup;
    AddPatch(&soup, -4.0, 0.0, 4, 6);
    AddPatch(&soup, 0.0, 4.0, 4, 6);
    for (size_t v = 35; v < soup.points.size(); ++v) soup.points[v].x() += gap;  // the second patch
    ASSERT_EQ(BoundaryEdgeCount(soup), 2 * (8 + 6) + 2 * 6);                      // cut open along x = 0
    const SoupRepairs r = RepairSurfaceSoup(&soup);
    EXPECT_EQ(r.welded, 7) << gap;  // the seam's seven vertices
    EXPECT_EQ(r.zipped, 0);
    EXPECT_EQ(r.flipped, 0);
    EXPECT_EQ(BoundaryEdgeCount(soup), 2 * (8 + 6)) << gap;  // the rectangle's outline only
    EXPECT_TRUE(ValidateSurfaceSoup(soup).ok());
  }
}

TEST(SoupRepair, TJunctionsAlongASeamAreClosedAndTheAreaKept) {
  // Left patch 3 rows, right patch 6: every second right seam vertex is in the middle of a
  // left seam edge (the height field is linear in y along x = 0, so it lies on it exactly).
  PolygonSoup soup;
  AddPatch(&soup, -4.0, 0.0, 4, 3);
  AddPatch(&soup, 0.0, 4.0, 4, 6);
  const Eigen::Vector3d area = VectorArea(soup);
  const SoupRepairs r = RepairSurfaceSoup(&soup);
  EXPECT_EQ(r.welded, 4);
  EXPECT_EQ(r.zipped, 3);
  EXPECT_EQ(BoundaryEdgeCount(soup), 2 * 8 + 3 + 6);
  EXPECT_TRUE(ValidateSurfaceSoup(soup).ok()) << ValidateSurfaceSoup(soup).message();
  EXPECT_NEAR((VectorArea(soup) - area).norm(), 0.0, 1e-12);
}

TEST(SoupRepair, ATJunctionOnACurvedSeamWithinTheChordsSagittaIsClosed) {
  // A seam bent in elevation: the right side's middle vertex sits 1e-4 of the chord's length
  // off the left side's chord (a CAD tessellation tolerance), and is inserted into it.
  PolygonSoup soup;
  soup.points = {{-1, 0, 0}, {0, 0, 0}, {0, 2, 0}, {1, 0, 0}, {1, 2, 0}, {0, 1, 2e-4}};
  soup.faces = {{0, 1, 2}, {1, 3, 5}, {3, 4, 5}, {5, 4, 2}};
  const SoupRepairs r = RepairSurfaceSoup(&soup);
  EXPECT_EQ(r.zipped, 1);
  EXPECT_EQ(BoundaryEdgeCount(soup), 5);
  EXPECT_TRUE(ValidateSurfaceSoup(soup).ok());
  // 2e-2 of the chord off is a gap, not a seam: left alone.
  soup.faces = {{0, 1, 2}, {1, 3, 5}, {3, 4, 5}, {5, 4, 2}};
  soup.points[5].z() = 4e-2;
  EXPECT_EQ(RepairSurfaceSoup(&soup).zipped, 0);
}

TEST(SoupRepair, PartsAreOrientedConsistentlyAndFacingUp) {
  PolygonSoup soup = testing::FlatGridSoup(4);
  for (size_t f = 0; f < soup.faces.size(); f += 3) std::reverse(soup.faces[f].begin(), soup.faces[f].end());
  SoupRepairs r = RepairSurfaceSoup(&soup);
  EXPECT_EQ(r.flipped, 11);  // faces 0, 3, ..., 30
  EXPECT_EQ(r.turned_up, 0);
  EXPECT_NEAR(VectorArea(soup).z(), 16.0, 1e-12);
  EXPECT_TRUE(ValidateSurfaceSoup(soup).ok());

  for (auto& f : soup.faces) std::reverse(f.begin(), f.end());  // the whole grid facing down
  r = RepairSurfaceSoup(&soup);
  EXPECT_EQ(r.flipped, 0);
  EXPECT_EQ(r.turned_up, 1);
  EXPECT_NEAR(VectorArea(soup).z(), 16.0, 1e-12);
  EXPECT_EQ(soup.faces[0], (std::vector<int>{0, 1, 6}));  // reversed back, not merely rotated
}

TEST(SoupRepair, AMoebiusBandIsLeftForValidationToRefuse) {
  PolygonSoup soup;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    for (const double s : {0.5, -0.5})
      soup.points.emplace_back((3.0 + s * std::cos(t / 2)) * std::cos(t), (3.0 + s * std::cos(t / 2)) * std::sin(t),
                               s * std::sin(t / 2));
  }
  for (int i = 0; i < n; ++i) {
    const int top = 2 * i, bottom = 2 * i + 1;
    const int next_top = i + 1 < n ? 2 * i + 2 : 1, next_bottom = i + 1 < n ? 2 * i + 3 : 0;  // the half twist
    soup.faces.push_back({top, bottom, next_bottom});
    soup.faces.push_back({top, next_bottom, next_top});
  }
  const auto faces = soup.faces;
  const SoupRepairs r = RepairSurfaceSoup(&soup);
  EXPECT_EQ(r.flipped, 0);
  EXPECT_EQ(soup.faces, faces);
  const Status s = ValidateSurfaceSoup(soup);
  EXPECT_NE(s.message().find("opposite orientations"), std::string::npos) << s.message();
}

TEST(SoupRepair, NeighboursOnOneTriangleAndSeparateRoofsAreNotWelded) {
  // Two roofs 1 cm apart (3e-4 of the diagonal): an expansion joint, not a seam.
  PolygonSoup soup;
  AddPatch(&soup, -4.0, 0.0, 4, 6);
  AddPatch(&soup, 0.01, 4.0, 4, 6);
  const int boundary = BoundaryEdgeCount(soup);
  SoupRepairs r = RepairSurfaceSoup(&soup);
  EXPECT_EQ(r.welded + r.zipped, 0);
  EXPECT_EQ(BoundaryEdgeCount(soup), boundary);
  // A sliver whose short edge is below the tolerance is not collapsed by welding.
  soup = testing::FlatGridSoup(2);
  soup.points.emplace_back(2.0, 1e-8, 0.0);
  soup.faces.push_back({2, 9, 5});  // vertices 2 (2, 0) and 9 share the sliver
  r = RepairSurfaceSoup(&soup);
  EXPECT_EQ(r.welded, 0);
  EXPECT_EQ(soup.faces.back(), (std::vector<int>{2, 9, 5}));
}

// A fuzzed PLY (vertex (1.4e-309, NaN, -1e6)) took 8.8 s to be refused: Eigen's maxCoeff
// skipped the NaN, and the grid of boundary edges looped over cells from floor(NaN).
TEST(SoupRepair, ANonFiniteCoordinateIsLeftForValidationAtOnce) {
  PolygonSoup fuzzed;  // the fuzzer's file, as read
  fuzzed.points = {{0, 0, 0}, {1, 0, 0}, {1.0000000000000018, 0, 0}, {1.0002441406251157, 6.365987373e-314, 4.243991582e-314},
                   {1.39067116156826e-309, NAN, -1048448.0}, {2.0, 0.005221755730531186, 0}};
  fuzzed.faces = {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}};
  const auto fuzzed_faces = fuzzed.faces;
  EXPECT_EQ(RepairSurfaceSoup(&fuzzed).welded, 0);
  EXPECT_EQ(fuzzed.faces, fuzzed_faces);
  for (const Eigen::Vector3d bad : {Eigen::Vector3d(1.39067e-309, NAN, -1.04845e6), Eigen::Vector3d(1, NAN, 0),
                                    Eigen::Vector3d(INFINITY, 0, 0), Eigen::Vector3d(1e300, 0, 0)}) {
    PolygonSoup soup = testing::FlatGridSoup(2);
    soup.points[2] = bad;  // a corner: on the boundary
    const auto faces = soup.faces;
    const SoupRepairs r = RepairSurfaceSoup(&soup);
    EXPECT_EQ(r.welded + r.zipped + r.flipped, 0);
    EXPECT_EQ(soup.faces, faces);
    EXPECT_EQ(SuggestWeldTolerance(soup), 0.0);
  }
}

TEST(SoupRepair, ASoupThatIsNotTrianglesIsLeftAlone) {
  PolygonSoup soup = testing::FlatGridSoup(2);
  soup.faces.push_back({0, 1, 2, 3, 4});
  std::reverse(soup.faces[0].begin(), soup.faces[0].end());
  const auto faces = soup.faces;
  const SoupRepairs r = RepairSurfaceSoup(&soup);
  EXPECT_EQ(r.flipped + r.welded + r.zipped, 0);
  EXPECT_EQ(soup.faces, faces);
}

// A dome (16 × 12 m, rise 3 m) exported as two NURBS patches would be: the left tessellated
// 8 × 8, the right 8 × 12 and written with its normals down, each with its own seam vertices.
// The seam is curved in elevation, so the right side's extra seam vertices sit up to 3 % of a
// chord off the left side's chords (and the left's off the right's).
PolygonSoup TwoPatchDome() {
  PolygonSoup soup;
  auto z = [](double x, double y) { return 3.0 * (1.0 - 0.5 * (x / 8) * (x / 8) - 0.5 * (y / 6) * (y / 6)); };
  auto patch = [&](double x0, double x1, int nx, int ny, bool flip) {
    const int base = static_cast<int>(soup.points.size());
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const double x = x0 + (x1 - x0) * i / nx, y = -6.0 + 12.0 * j / ny;
        soup.points.emplace_back(x, y, z(x, y));
      }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = base + j * (nx + 1) + i, c = a + nx + 2;
        for (std::vector<int> t : {std::vector<int>{a, a + 1, c}, std::vector<int>{a, c, c - 1}}) {
          if (flip) std::reverse(t.begin(), t.end());
          soup.faces.push_back(t);
        }
      }
  };
  patch(-8.0, 0.0, 8, 8, false);
  patch(0.0, 8.0, 8, 12, true);
  return soup;
}

// Through the executable: refused in one line naming the key that mends it and its value; with
// that tolerance, read as one roof with one outline.
TEST(SoupRepairCli, ACurvedSeamWithTJunctionsNeedsTheExportsToleranceAndThenIsOneRoof) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.obj", testing::ObjText(TwoPatchDome()));
  testing::WriteFile(dir, "c.yaml", "surface:\n  file: dome.obj\nlayout:\n  spacing: 1.5\n");
  testing::CliResult r = testing::RunPqlayout(dir, "run c.yaml --out refused --until surface -q");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(testing::CountLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("dome.obj: non-manifold vertex"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/refused"));
  // It measures how far the T-junctions lie off the other side's chords and names the value.
  const std::string key = "surface.weld_tolerance: ";
  const size_t at = r.err.find("m off the other side's edges: " + key);
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string suggested = r.err.substr(r.err.find(key, at) + key.size(), 5);
  EXPECT_EQ(suggested, "0.031");  // 1.5 × the farthest, 0.021 m: 1.4 % of a 1.5 m chord

  r = testing::RunPqlayout(dir, "run c.yaml --out result --until surface -q --set surface.weld_tolerance=" + suggested);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(testing::ReadFile(dir + "/result/report.json"));
  const auto& s = report["stages"]["surface"];
  EXPECT_EQ(s["n_parts"].get<int>(), 1);
  ASSERT_EQ(s["boundary_loops"].size(), 1u);
  EXPECT_EQ(s["n_boundary_vertices"].get<int>(), 2 * 16 + 8 + 12);  // the rim: 16 edges along x twice, 8 and 12 across
  EXPECT_LT(s["facing_angle_deg"].get<double>(), 1.0);  // the flipped patch faces up with the rest
  const std::string warnings = report["warnings"].dump();
  EXPECT_NE(warnings.find("welded 5 boundary vertices"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("closed 12 T-junctions"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("oriented against their neighbours"), std::string::npos) << warnings;
}

}  // namespace
}  // namespace pqlayout
