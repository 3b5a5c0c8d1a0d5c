// Bracing of free edges (geometry/edge_bracing.h) on a sheared 3 × 3 grid, where every answer
// can be checked: which quads are cut, by which diagonal, and what stays.
#include <gtest/gtest.h>

#include <vector>

#include "geometry/edge_bracing.h"
#include "tests/extraction_test_helpers.h"

namespace pqlayout {
namespace {

// 3 × 3 parallelograms (shear 0.4: the diagonal (i+1, j)–(i, j+1) is the shorter one, and
// cutting along it gives the better triangles).
ExtractedMesh ShearedGrid() { return extraction_test::QuadGrid3(0.4); }

int FacesWithSides(const PolyMesh& mesh, size_t sides) {
  int count = 0;
  for (const auto f : mesh.faces()) count += mesh.valence(f) == sides;
  return count;
}

TEST(EdgeBracing, CutsTheQuadsOnAFreeEdgeByTheShorterDiagonal) {
  ExtractedMesh out = ShearedGrid();
  std::vector<bool> free(16, false);
  for (int i = 0; i <= 3; ++i) free[12 + i] = true;  // the top row
  EXPECT_EQ(BraceFreeEdges(free, &out), 3);
  EXPECT_EQ(out.stats.braced_quads, 3);
  EXPECT_EQ(out.mesh.n_vertices(), 16u);
  EXPECT_EQ(FacesWithSides(out.mesh, 4), 6);
  EXPECT_EQ(FacesWithSides(out.mesh, 3), 6);
  for (int i = 0; i < 3; ++i) {  // each top quad (8+i, 9+i, 13+i, 12+i) by 9+i – 12+i
    const auto h = out.mesh.find_halfedge(VertexHandle(9 + i), VertexHandle(12 + i));
    EXPECT_TRUE(h.is_valid()) << i;
    EXPECT_FALSE(out.mesh.find_halfedge(VertexHandle(8 + i), VertexHandle(13 + i)).is_valid()) << i;
  }
  for (const auto f : out.mesh.faces()) EXPECT_TRUE(out.mesh.valence(f) == 4 || out.mesh.valence(f) == 3);
}

// A quad touching the free stretch only at a vertex keeps its shape; nothing free, nothing cut.
TEST(EdgeBracing, AFreeVertexIsNotAFreeEdge) {
  ExtractedMesh out = ShearedGrid();
  std::vector<bool> free(16, false);
  free[12] = free[13] = true;  // the top edge of the first top quad only
  EXPECT_EQ(BraceFreeEdges(free, &out), 1);
  EXPECT_EQ(FacesWithSides(out.mesh, 3), 2);
  EXPECT_EQ(FacesWithSides(out.mesh, 4), 8);

  ExtractedMesh untouched = ShearedGrid();
  EXPECT_EQ(BraceFreeEdges(std::vector<bool>(16, false), &untouched), 0);
  EXPECT_EQ(FacesWithSides(untouched.mesh, 4), 9);
  EXPECT_EQ(untouched.stats.braced_quads, 0);
}

// Free vertices joined by an interior edge (a free stretch seen across a corner cell) are not
// a free edge: only mesh boundary edges count.
TEST(EdgeBracing, OnlyBoundaryEdgesCount) {
  ExtractedMesh out = ShearedGrid();
  std::vector<bool> free(16, false);
  free[5] = free[6] = true;  // interior vertices joined by an interior edge
  EXPECT_EQ(BraceFreeEdges(free, &out), 0);
  EXPECT_EQ(FacesWithSides(out.mesh, 4), 9);
}

// Stretches: the top row and the right column are free, joined at the top-right corner (one
// stretch); with the corner vertex supported they are two, and the corner quad, whose two
// boundary edges both end at the supported corner, is on neither.
TEST(EdgeBracing, QuadsAreGroupedByFreeStretch) {
  const ExtractedMesh grid = ShearedGrid();
  std::vector<bool> free(16, false);
  for (int i = 0; i <= 3; ++i) free[12 + i] = free[4 * i + 3] = true;  // top row, right column
  std::vector<std::vector<int>> groups = FreeEdgeQuads(free, grid.mesh);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].size(), 5u);  // faces 2, 5, 6, 7, 8

  free[15] = false;  // the corner supported
  groups = FreeEdgeQuads(free, grid.mesh);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0], (std::vector<int>{2, 5}));  // the right column
  EXPECT_EQ(groups[1], (std::vector<int>{6, 7}));  // the top row
}

// A boundary triangle between two quads of a free edge does not break the stretch.
TEST(EdgeBracing, ATriangleOnTheEdgeDoesNotEndTheStretch) {
  ExtractedMesh grid = ShearedGrid();
  ASSERT_EQ(CutQuads({7}, &grid), 1);  // the middle top quad becomes two triangles
  std::vector<bool> free(16, false);
  for (int i = 0; i <= 3; ++i) free[12 + i] = true;
  const std::vector<std::vector<int>> groups = FreeEdgeQuads(free, grid.mesh);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].size(), 2u);
  EXPECT_EQ(grid.stats.braced_quads, 1);
  EXPECT_EQ(CutQuads({}, &grid), 0);
  EXPECT_EQ(FacesWithSides(grid.mesh, 3), 2);
}

}  // namespace
}  // namespace pqlayout
