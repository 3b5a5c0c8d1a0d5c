// The clean-up of the extracted polygons (geometry/quad_cleanup.h) on small hand-made meshes:
// floating parts, the collapse's refusals, large cells cut into quads.
#include "geometry/quad_cleanup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/polygon_shape.h"

namespace pqlayout {

// A part of the extracted mesh that touches no reference boundary (an island ringed by cells
// left out where the level sets fold over) is dropped; a part joined to the boundary through
// interior faces stays.
TEST(QuadCleanup, DropsOnlyPartsThatTouchNoBoundary) {
  extraction_internal::Polygons m;
  for (int v = 0; v < 10; ++v) {
    m.position.emplace_back(v, v % 3, 0.0);
    m.origin.push_back(QuadMeshVertex());
  }
  m.origin[0].on_boundary = true;
  m.faces = {{0, 1, 2, 3}, {2, 3, 4, 5}, {6, 7, 8, 9}};
  EXPECT_EQ(extraction_internal::DropFloatingParts(&m), 1);
  ASSERT_EQ(m.faces.size(), 2u);
  EXPECT_EQ(m.faces[0], (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(m.faces[1], (std::vector<int>{2, 3, 4, 5}));
  m.origin[0].on_boundary = false;  // nothing holds the rest either
  EXPECT_EQ(extraction_internal::DropFloatingParts(&m), 2);
  EXPECT_TRUE(m.faces.empty());
}

// Two rows of five unit quads (vertices 0‥17, row by row) with vertex 18 just above the
// middle of edge (8, 9): the cell above is the pentagon (8, 18, 9, 15, 14) over the triangle
// (8, 9, 18). Vertex 18 has two neighbours and the two faces only: it goes, the triangle with
// it, and the pentagon is the quad (8, 9, 15, 14) again. On the reference boundary it stays.
TEST(QuadCleanup, AnInteriorValence2VertexGoesWithItsTriangle) {
  const auto notched = [](bool on_boundary) {
    extraction_internal::Polygons m;
    for (int row = 0; row < 3; ++row)
      for (int i = 0; i < 6; ++i) {
        m.position.emplace_back(i, row, 0.0);
        m.origin.push_back(QuadMeshVertex());
        m.origin.back().on_boundary = row != 1 || i == 0 || i == 5;
      }
    m.position.emplace_back(2.5, 1.3, 0.0);
    m.origin.push_back(QuadMeshVertex());
    m.origin.back().on_boundary = on_boundary;
    for (int row = 0; row < 2; ++row)
      for (int i = 0; i < 5; ++i) m.faces.push_back({6 * row + i, 6 * row + i + 1, 6 * row + i + 7, 6 * row + i + 6});
    m.faces[7] = {8, 18, 9, 15, 14};
    m.faces.push_back({8, 9, 18});
    return m;
  };
  extraction_internal::Polygons m = notched(false);
  EXPECT_EQ(extraction_internal::DropInteriorValence2Vertices(&m), 1);
  ASSERT_EQ(m.faces.size(), 10u);
  EXPECT_EQ(m.faces[7], (std::vector<int>{8, 9, 15, 14}));
  for (const auto& face : m.faces) EXPECT_EQ(face.size(), 4u);
  extraction_internal::Polygons kept = notched(true);
  EXPECT_EQ(extraction_internal::DropInteriorValence2Vertices(&kept), 0);
  EXPECT_EQ(kept.faces.size(), 11u);
}

// The collapse's refusals, named: on a 3 × 3 grid of quads the interior edge (5, 6) may
// collapse; as a chord between two reference-boundary points, or between two corners, not.
TEST(QuadCleanup, CollapseBlockerNamesWhyAnEdgeStays) {
  extraction_internal::Polygons m;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      m.position.emplace_back(i, j, 0.0);
      m.origin.push_back(QuadMeshVertex());
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.faces.push_back({4 * j + i, 4 * j + i + 1, 4 * j + i + 5, 4 * j + i + 4});
  EXPECT_EQ(extraction_internal::CollapseBlocker(m, 5, 6), nullptr);
  EXPECT_STREQ(extraction_internal::CollapseBlocker(m, 0, 5), "not an edge");
  EXPECT_EQ(extraction_internal::CollapseBlocker(m, 1, 5), nullptr);  // 5 moves onto the boundary point 1
  m.origin[5].on_boundary = m.origin[6].on_boundary = true;
  EXPECT_NE(std::string(extraction_internal::CollapseBlocker(m, 5, 6)).find("chord"), std::string::npos);
  m.origin[0].corner = m.origin[1].corner = true;
  EXPECT_STREQ(extraction_internal::CollapseBlocker(m, 0, 1), "both ends are boundary corners");
}

// A star hexagon (corners at angles k·60°, the even ones `far` from the origin, corner 0 at
// far0, the odd ones 0.6) inside a ring of six quads (the corners scaled by 3), so that it
// touches no boundary: vertices 0–5 the hexagon, 6–11 the ring; face 0 the hexagon.
static extraction_internal::Polygons StarHexagonInARing(double far0, double far) {
  extraction_internal::Polygons m;
  for (int k = 0; k < 6; ++k) {
    const double r = k == 0 ? far0 : (k % 2 == 0 ? far : 0.6), a = k * M_PI / 3.0;
    m.position.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    m.origin.push_back(QuadMeshVertex());
  }
  for (int k = 0; k < 6; ++k) {
    m.position.push_back(3.0 * m.position[k]);
    m.origin.push_back(QuadMeshVertex());
  }
  m.faces.push_back({0, 1, 2, 3, 4, 5});
  for (int k = 0; k < 6; ++k) m.faces.push_back({(k + 1) % 6, k, 6 + k, 6 + (k + 1) % 6});
  return m;
}

// The Great Court paper layout's boundary 9-gon (2026-12-06, corners rounded to cm, flattened
// onto z = 0): two corners on the Reading Room's ring (the one boundary side, 0.83 m), the
// others inside, a ring of quads (corners ×2 about the centroid) on every other side. Its best
// cut into quads and a triangle has a corner below 20°, so it used to stay a 10 m × 5 m 9-gon;
// a boundary cell of seven or more sides now takes its best cut down to 10°.
TEST(QuadCleanup, ABoundaryNineGonWithNoCutAbove20DegreesTakesItsBestCut) {
  const std::vector<Eigen::Vector2d> corners{{17.73, 16.03}, {21.28, 15.02}, {25.57, 14.93}, {24.13, 17.85}, {19.39, 18.10},
                                             {16.74, 20.88}, {15.00, 18.45}, {15.23, 16.21}, {15.82, 15.62}};
  extraction_internal::Polygons m;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& c : corners) centroid += Eigen::Vector3d(c.x(), c.y(), 0.0) / 9.0;
  for (const auto& c : corners) m.position.emplace_back(c.x(), c.y(), 0.0);
  for (int k = 0; k < 9; ++k) m.position.push_back(centroid + 2.0 * (m.position[k] - centroid));
  m.origin.resize(18);
  m.faces.push_back({0, 1, 2, 3, 4, 5, 6, 7, 8});
  for (int k = 0; k < 9; ++k)
    if (k != 7) m.faces.push_back({(k + 1) % 9, k, 9 + k, 9 + (k + 1) % 9});  // side 7–8 is the boundary
  const auto [interior, boundary] = extraction_internal::SplitLargePolygons(extraction_internal::kMinResplitAngle, &m);
  EXPECT_EQ(interior, 0);
  EXPECT_EQ(boundary, 1);
  ASSERT_EQ(m.faces.size(), 8u + 4u);  // the ring, three quads and a triangle
  int triangles = 0;
  double worst = M_PI;
  for (const auto& face : m.faces) {
    if (std::any_of(face.begin(), face.end(), [](int v) { return v >= 9; })) continue;  // the ring
    EXPECT_LE(face.size(), 4u);
    triangles += face.size() == 3;
    if (face.size() == 4) worst = std::min(worst, ShapeAngle(m.position, face));
  }
  EXPECT_EQ(triangles, 1);
  EXPECT_GE(worst, extraction_internal::kLastResortCutAngle);
  EXPECT_LT(worst, extraction_internal::kMinResplitAngle);  // the last resort, not the usual cut
}

// The wavy roof × curvature's interior 8-gon (corners rounded to cm; angles 42°, 220°, 171°,
// 92°, 117°, 174°, 90°, 175°): no two diagonals cut it with every angle in 20°–160°, nor does
// a vertex joined to every other corner (a reflex or flat corner is left in a quad either
// way). A quad cut off by one diagonal and the hexagon left split round a centre vertex
// (valence 3) does: 4 quads. A ring of quads (the corners scaled ×3 about the centroid) keeps
// it off the boundary.
TEST(QuadCleanup, AnOctagonWithAReflexCornerGetsAQuadAndACentreVertex) {
  extraction_internal::Polygons m;
  const double corners[8][3] = {{10.67, -7.08, 0.12}, {10.63, -4.82, 0.15}, {11.6, -3.6, 0.15}, {12.48, -2.09, 0.22},
                                {11.33, -1.38, 0.44}, {9.24, -2.65, 0.45},  {7.83, -3.74, 0.61}, {8.96, -5.23, 0.41}};
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& c : corners) centroid += Eigen::Vector3d(c[0], c[1], c[2]) / 8.0;
  for (int ring = 0; ring < 2; ++ring)
    for (const auto& c : corners) {
      m.position.push_back(centroid + (ring ? 3.0 : 1.0) * (Eigen::Vector3d(c[0], c[1], c[2]) - centroid));
      m.origin.push_back(QuadMeshVertex());
    }
  m.faces.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  for (int k = 0; k < 8; ++k) m.faces.push_back({(k + 1) % 8, k, 8 + k, 8 + (k + 1) % 8});
  const auto [interior, boundary] = extraction_internal::SplitLargePolygons(extraction_internal::kMinResplitAngle, &m);
  EXPECT_EQ(interior, 1);
  EXPECT_EQ(boundary, 0);
  ASSERT_EQ(m.position.size(), 17u);
  EXPECT_TRUE(m.origin[16].centre);
  ASSERT_EQ(m.faces.size(), 12u);
  int around = 0;
  for (const auto& face : m.faces) {
    EXPECT_EQ(face.size(), 4u);
    around += std::count(face.begin(), face.end(), 16);
    if (std::all_of(face.begin(), face.end(), [](int v) { return v < 8 || v == 16; }))
      EXPECT_GE(ShapeAngle(m.position, face), extraction_internal::kMinResplitAngle);
  }
  EXPECT_EQ(around, 3);
}

// An interior hexagon with corners alternately 1 and 0.6 from its centre: every cut by a
// diagonal leaves a quad with a 13° corner (below the 20° bound), so it used to stay a
// hexagon; around a centre vertex joined to the three near corners each quad's smallest
// corner or supplement is 60°. A ring of quads keeps the hexagon off the boundary.
TEST(QuadCleanup, AHexagonNoDiagonalCutsWellGetsACentreVertex) {
  extraction_internal::Polygons m = StarHexagonInARing(1.0, 1.0);
  const auto [interior, boundary] = extraction_internal::SplitLargePolygons(extraction_internal::kMinResplitAngle, &m);
  EXPECT_EQ(interior, 1);
  EXPECT_EQ(boundary, 0);
  ASSERT_EQ(m.position.size(), 13u);
  EXPECT_TRUE(m.origin[12].centre);
  EXPECT_LT(m.position[12].norm(), 1e-12);  // the hexagon's centroid
  ASSERT_EQ(m.faces.size(), 9u);
  int around = 0;
  for (const auto& face : m.faces) {
    EXPECT_EQ(face.size(), 4u);
    const auto at = std::find(face.begin(), face.end(), 12);
    if (at == face.end()) continue;
    ++around;
    const size_t k = at - face.begin();  // the centre's neighbours: the near corners 1, 3, 5
    EXPECT_EQ(face[(k + 1) % 4] % 2, 1);
    EXPECT_EQ(face[(k + 3) % 4] % 2, 1);
  }
  EXPECT_EQ(around, 3);
  // A regular hexagon is cut by a diagonal (two quads, 60° corners): no centre vertex.
  extraction_internal::Polygons regular = m;
  regular.position.resize(12);
  regular.origin.resize(12);
  for (int k = 0; k < 12; ++k) regular.position[k] = (k < 6 ? 1.0 : 3.0) * Eigen::Vector3d(std::cos(k * M_PI / 3.0), std::sin(k * M_PI / 3.0), 0.0);
  regular.faces = {{0, 1, 2, 3, 4, 5}};
  for (int k = 0; k < 6; ++k) regular.faces.push_back({(k + 1) % 6, k, 6 + k, 6 + (k + 1) % 6});
  EXPECT_EQ(extraction_internal::SplitLargePolygons(extraction_internal::kMinResplitAngle, &regular).first, 1);
  EXPECT_EQ(regular.position.size(), 12u);
  EXPECT_EQ(regular.faces.size(), 8u);
}

// The same star hexagon with one far corner at 2.5 instead of 1: the corners' average moves
// 0.25 towards it, where the quads round a centre vertex get an 11° corner; at the star's own
// centre their worst corner is 26.6° (measured by hand with ShapeAngle's rule). CentreSplit's
// search must find such a place: three quads, every corner and supplement ≥ 20°.
TEST(QuadCleanup, ACentreVertexMovesOffTheCornersAverageIfThatCutsBadly) {
  extraction_internal::Polygons m = StarHexagonInARing(2.5, 1.0);
  Eigen::Vector3d average = Eigen::Vector3d::Zero();
  for (int k = 0; k < 6; ++k) average += m.position[k] / 6.0;
  const auto [interior, boundary] = extraction_internal::SplitLargePolygons(extraction_internal::kMinResplitAngle, &m);
  EXPECT_EQ(interior, 1);
  ASSERT_EQ(m.position.size(), 13u);
  EXPECT_TRUE(m.origin[12].centre);
  EXPECT_GT((m.position[12] - average).norm(), 0.1);  // not at the corners' average
  EXPECT_LT(m.position[12].norm(), 0.35);             // near the star's centre
  ASSERT_EQ(m.faces.size(), 9u);
  int around = 0;
  for (const auto& face : m.faces) {
    EXPECT_EQ(face.size(), 4u);
    if (std::find(face.begin(), face.end(), 12) == face.end()) continue;  // the ring (a fixture)
    ++around;
    EXPECT_GE(ShapeAngle(m.position, face), extraction_internal::kMinResplitAngle);
  }
  EXPECT_EQ(around, 3);
}

}  // namespace pqlayout
