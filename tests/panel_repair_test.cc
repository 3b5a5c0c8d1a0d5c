// Panels that planarisation degenerated, repaired topologically (geometry/panel_repair.h) and
// counted (MeasurePanelShapes): hand-built 2 × 1 and 3 × 3 grids of unit quads, each repair's
// known result. Split from planarize_test.cc (2026-12-06), which had passed 500 lines.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "geometry/mesh_metrics.h"
#include "geometry/panel_repair.h"
#include "geometry/planarity.h"
#include "problems/planarize.h"
#include "tests/quad_grid.h"

namespace pqlayout {
namespace {

using testing::QuadGrid;

// Panel shapes after planarisation (MeasurePanelShapes): a 2 × 1 grid of unit quads. With the
// middle column's two vertices swapped both quads fold into bow-ties (2 folded faces, each of
// the two moved by 1); with
// the right quad squeezed to a bottom edge of 0.05 it stays convex (none folded), the
// shortest edge is 0.05 and it is counted below min_edge = 0.2; the grid as extracted has neither.
TEST(PanelShapes, AFoldedQuadAndAShortEdgeAreCounted) {
  ExtractedMesh grid = QuadGrid(2, 1, 1.0, [](double, double) { return 0.0; });
  std::vector<Eigen::Vector3d> start;
  for (const auto v : grid.mesh.vertices()) start.push_back(ToEigen(grid.mesh.point(v)));
  PlanarizeReport same;
  MeasurePanelShapes(grid.mesh, start, 1.0, 0.2, &same);
  EXPECT_EQ(same.folded_faces, 0);
  EXPECT_EQ(same.max_displacement, 0.0);
  EXPECT_EQ(same.edges_below_min_edge, 0);
  EXPECT_DOUBLE_EQ(same.edge_length_min, 1.0);
  const auto at = [&](double x, double y) -> VertexHandle {
    for (const auto v : grid.mesh.vertices())
      if ((ToEigen(grid.mesh.point(v)) - Eigen::Vector3d(x, y, 0.0)).norm() < 1e-9) return v;
    ADD_FAILURE() << "no vertex at " << x << ", " << y;
    return VertexHandle();
  };
  const VertexHandle a = at(1, 0), b = at(1, 1), c = at(2, 0);
  grid.mesh.set_point(a, {1.0, 1.0, 0.0});  // the middle column's two vertices swapped: both quads fold
  grid.mesh.set_point(b, {1.0, 0.0, 0.0});
  PlanarizeReport folded;
  MeasurePanelShapes(grid.mesh, start, 1.0, 0.2, &folded);
  EXPECT_EQ(folded.folded_faces, 2);
  EXPECT_EQ(folded.folded_at.size(), 2u);
  EXPECT_DOUBLE_EQ(folded.max_displacement, 1.0);  // from `start`, whatever moved them
  EXPECT_DOUBLE_EQ(folded.max_displacement_edges, 1.0);  // unit edges
  grid.mesh.set_point(a, {1.0, 0.0, 0.0});
  grid.mesh.set_point(b, {1.0, 1.0, 0.0});
  grid.mesh.set_point(c, {1.05, 0.0, 0.0});  // the right quad squeezed, still convex
  PlanarizeReport squeezed;
  MeasurePanelShapes(grid.mesh, start, 1.0, 0.2, &squeezed);
  EXPECT_EQ(squeezed.folded_faces, 0);
  EXPECT_NEAR(squeezed.edge_length_min, 0.05, 1e-12);
  EXPECT_GE(squeezed.edges_below_min_edge, 1);
}

std::map<int, int> FaceSides(const PolyMesh& mesh) {
  std::map<int, int> sides;
  for (const auto f : mesh.faces()) ++sides[static_cast<int>(mesh.valence(f))];
  return sides;
}

// CloseShortEdges: in a 2 × 1 grid whose right quad planarisation squeezed to a bottom edge of
// 0.01 (a boundary vertex slid next to the corner), that edge is closed and the corner keeps
// its place: one quad and one triangle, 5 vertices, the start positions carried to the
// vertices left. With a threshold of 0.005 nothing is closed.
TEST(PanelRepair, AClosedEdgeMakesTheQuadTheTriangleItIs) {
  ExtractedMesh grid = QuadGrid(2, 1, 1.0, [](double, double) { return 0.0; });
  std::vector<Eigen::Vector3d> start;
  for (const auto v : grid.mesh.vertices()) start.push_back(ToEigen(grid.mesh.point(v)));
  grid.mesh.set_point(VertexHandle(1), {1.99, 0.0, 0.0});  // (1, 0) slid next to the corner (2, 0)
  std::vector<Eigen::Vector3d> carried = start;
  EXPECT_EQ(CloseShortEdges(0.005, &grid, &carried), 0);
  EXPECT_EQ(CloseShortEdges(0.05, &grid, &carried), 1);
  EXPECT_EQ(grid.mesh.n_vertices(), 5u);
  EXPECT_EQ(grid.origin.size(), 5u);
  ASSERT_EQ(carried.size(), 5u);
  EXPECT_EQ(FaceSides(grid.mesh), (std::map<int, int>{{3, 1}, {4, 1}}));
  for (const auto v : grid.mesh.vertices()) {  // the corner kept its place; (1, 0) is gone
    EXPECT_GT((ToEigen(grid.mesh.point(v)) - Eigen::Vector3d(1.99, 0.0, 0.0)).norm(), 1e-9);
    EXPECT_TRUE(std::find(start.begin(), start.end(), carried[v.idx()]) != start.end());
  }
}

// CloseShortEdges on a chord: a quad on a 0.01-long interior edge between two boundary
// vertices, whose far side is an ear (a needle triangle, 0.2 long, with its other two edges on
// the boundary).
// The collapse rules refuse the chord, so the ear is dropped and the chord, now a boundary
// edge, closed: one triangle left. With the ear's tip a corner of the reference nothing is
// closed.
TEST(PanelRepair, AShortChordDropsItsEarAndCloses) {
  const auto build = [](bool tip_is_corner) {
    ExtractedMesh m;
    const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {0.01, 0, 0}, {0.005, -0.2, 0}, {0.5, 1, 0}, {-0.5, 1, 0}};
    int rejected = 0;
    m.mesh = BuildPolyMesh(p, {{0, 2, 1}, {0, 1, 3, 4}}, &rejected);
    m.origin.resize(5);
    for (auto& o : m.origin) o.on_boundary = true;
    m.origin[2].corner = tip_is_corner;
    return m;
  };
  ExtractedMesh ear = build(false);
  std::vector<Eigen::Vector3d> start;
  for (const auto v : ear.mesh.vertices()) start.push_back(ToEigen(ear.mesh.point(v)));
  EXPECT_EQ(CloseShortEdges(0.05, &ear, &start), 2);  // the ear, then the chord
  EXPECT_EQ(FaceSides(ear.mesh), (std::map<int, int>{{3, 1}}));
  EXPECT_EQ(ear.mesh.n_vertices(), 3u);
  EXPECT_EQ(start.size(), 3u);
  ExtractedMesh corner = build(true);
  std::vector<Eigen::Vector3d> carried = start;
  carried.resize(5);
  EXPECT_EQ(CloseShortEdges(0.05, &corner, &carried), 0);
  EXPECT_EQ(FaceSides(corner.mesh), (std::map<int, int>{{3, 1}, {4, 1}}));
}

// CutDarts: a planar quad with one reflex corner becomes the two triangles on either side of
// the diagonal from that corner (both convex); a convex quad and a bow-tie are left alone.
TEST(PanelRepair, ADartIsCutIntoItsTwoTriangles) {
  ExtractedMesh grid = QuadGrid(2, 1, 1.0, [](double, double) { return 0.0; });
  grid.mesh.set_point(VertexHandle(4), {0.3, 0.3, 0.0});  // (1, 1) pushed inside the left quad: a dart
  EXPECT_EQ(CutDarts(&grid), 1);
  EXPECT_EQ(FaceSides(grid.mesh), (std::map<int, int>{{3, 2}, {4, 1}}));
  for (const auto f : grid.mesh.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (const auto v : grid.mesh.fv_range(f)) p.push_back(ToEigen(grid.mesh.point(v)));
    if (p.size() == 3) EXPECT_GT((p[1] - p[0]).cross(p[2] - p[1]).z(), 0.0);  // convex, facing up
  }
  ExtractedMesh bowtie = QuadGrid(2, 1, 1.0, [](double, double) { return 0.0; });
  bowtie.mesh.set_point(VertexHandle(1), {1.0, 1.0, 0.0});  // the middle column swapped
  bowtie.mesh.set_point(VertexHandle(4), {1.0, 0.0, 0.0});
  EXPECT_EQ(CutDarts(&bowtie), 0);
  ExtractedMesh convex = QuadGrid(2, 1, 1.0, [](double, double) { return 0.0; });
  EXPECT_EQ(CutDarts(&convex), 0);
}

// SplitFoldedPanels: in a 2 × 1 grid whose middle column's two vertices swapped (both quads
// bow-ties), each quad becomes the two triangles of a diagonal, vertices unchanged; the grid
// as extracted and a quad with a short edge but every corner still convex are left alone.
TEST(PanelRepair, AFoldedQuadIsCutIntoTriangles) {
  ExtractedMesh grid = QuadGrid(2, 1, 1.0, [](double, double) { return 0.0; });
  std::vector<Eigen::Vector3d> start;
  for (const auto v : grid.mesh.vertices()) start.push_back(ToEigen(grid.mesh.point(v)));
  EXPECT_EQ(SplitFoldedPanels(start, &grid), 0);
  grid.mesh.set_point(VertexHandle(2), {1.05, 0.0, 0.0});  // (2, 0) slid next to (1, 0): convex still
  EXPECT_EQ(SplitFoldedPanels(start, &grid), 0);
  grid.mesh.set_point(VertexHandle(2), ToOpenMesh(start[2]));
  grid.mesh.set_point(VertexHandle(1), {1.0, 1.0, 0.0});  // the middle column swapped
  grid.mesh.set_point(VertexHandle(4), {1.0, 0.0, 0.0});
  EXPECT_EQ(SplitFoldedPanels(start, &grid), 2);
  EXPECT_EQ(FaceSides(grid.mesh), (std::map<int, int>{{3, 4}}));
  EXPECT_EQ(grid.mesh.n_vertices(), 6u);
  EXPECT_EQ(grid.stats.rejected_faces, 0);
}

// SplitWarpedPanels: in a 2 × 1 grid of unit quads (right quad 1–2–5–4), lifting vertex 5 =
// (2, 1) by 0.3 warps the right quad (δ = 0.103) and leaves the left one planar: only the right
// quad is cut, into two triangles facing up, along 2–4 (smallest angle 45°; along 1–5: 43.8°).
// With vertex 5 also pushed out to x = 2.8 the cut stays on 2–4 (1–5: 22.4°); with vertex 2
// pushed out to x = 2.8 instead it moves to 1–5 (43.8° against 25.7°). A threshold above δ,
// or 0, cuts nothing.
TEST(PanelRepair, AWarpedQuadIsCutAlongItsBetterDiagonal) {
  using V = Eigen::Vector3d;
  // Which diagonal of the right quad was cut: {1, 5} or {2, 4}; {} if none.
  const auto diagonal = [](const ExtractedMesh& grid) {
    std::set<int> common = {1, 2, 4, 5};
    int triangles = 0;
    for (const auto f : grid.mesh.faces()) {
      std::set<int> ids;
      for (const auto v : grid.mesh.fv_range(f)) ids.insert(v.idx());
      const int missing = !ids.count(1) + !ids.count(2) + !ids.count(4) + !ids.count(5);
      if (ids.size() != 3 || missing != 1) continue;  // not one of the right quad's triangles
      ++triangles;
      std::set<int> both;
      for (const int v : common)
        if (ids.count(v)) both.insert(v);
      common = both;
      std::vector<V> p;
      for (const auto v : grid.mesh.fv_range(f)) p.push_back(ToEigen(grid.mesh.point(v)));
      EXPECT_GT((p[1] - p[0]).cross(p[2] - p[0]).z(), 0.0);  // facing up, as the quad did
    }
    return triangles == 2 ? common : std::set<int>{};
  };
  const auto warped = [](V five, V two) {
    ExtractedMesh grid = QuadGrid(2, 1, 1.0, [](double, double) { return 0.0; });
    grid.mesh.set_point(VertexHandle(5), ToOpenMesh(five));
    grid.mesh.set_point(VertexHandle(2), ToOpenMesh(two));
    return grid;
  };
  ExtractedMesh grid = warped({2.0, 1.0, 0.3}, {2.0, 0.0, 0.0});
  const double delta = QuadPlanarityDelta(V(1, 0, 0), V(2, 0, 0), V(2, 1, 0.3), V(1, 1, 0));
  EXPECT_NEAR(delta, 0.3 / std::sqrt(4.18) / (0.5 * (std::sqrt(2.09) + std::sqrt(2.0))), 1e-12);  // 0.103
  EXPECT_EQ(SplitWarpedPanels(delta + 1e-9, &grid), 0);
  EXPECT_EQ(SplitWarpedPanels(0.0, &grid), 0);
  EXPECT_EQ(QuadFraction(grid.mesh), 1.0);
  ASSERT_EQ(SplitWarpedPanels(0.05, &grid), 1);
  EXPECT_EQ(FaceSides(grid.mesh), (std::map<int, int>{{3, 2}, {4, 1}}));
  EXPECT_EQ(CountFaces(grid.mesh, 3), 2);  // geometry/mesh_metrics.h, the planarize stage's counts
  EXPECT_EQ(CountFaces(grid.mesh, 5), 0);
  EXPECT_DOUBLE_EQ(QuadFraction(grid.mesh), 1.0 / 3.0);
  EXPECT_EQ(grid.mesh.n_vertices(), 6u);
  EXPECT_EQ(diagonal(grid), (std::set<int>{2, 4}));
  grid = warped({2.8, 1.0, 0.3}, {2.0, 0.0, 0.0});
  ASSERT_EQ(SplitWarpedPanels(0.05, &grid), 1);
  EXPECT_EQ(diagonal(grid), (std::set<int>{2, 4}));
  grid = warped({2.0, 1.0, 0.3}, {2.8, 0.0, 0.0});
  ASSERT_EQ(SplitWarpedPanels(0.05, &grid), 1);
  EXPECT_EQ(diagonal(grid), (std::set<int>{1, 5}));
}

}  // namespace
}  // namespace pqlayout
