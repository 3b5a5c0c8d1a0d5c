// Quad-dominant mesh extraction (geometry/quad_extraction.h) on known answers: straight
// level lines on a flat square give exactly the grid, on a disk and an annulus a manifold
// mesh of the right topology; planarity δ on hand-computed polygons; the Great Court end to
// end through the real membrane, guidance and level-set solves.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <set>

#include "geometry/boundary_refinement.h"
#include "geometry/planarity.h"
#include "geometry/quad_cleanup.h"
#include "geometry/quad_extraction.h"
#include "problems/guidance.h"
#include "problems/levelset.h"
#include "problems/membrane.h"
#include "tests/extraction_test_helpers.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::FlatGridSoup;
using testing::GeneratedMesh;
using testing::ToMesh;
using namespace extraction_test;

// The square [0, n h]² with φ = x / h, ψ = y / h must give exactly the n × n grid.
void ExpectExactGrid(int cells, double cell, double h) {
  const SurfaceModel s(ScaledGrid(cells, cell));
  const int n = static_cast<int>(std::lround(cells * cell / h));
  std::vector<double> phi, psi;
  RotatedCoordinates(s, 0.0, h, 0.0, &phi, &psi);
  ExtractedMesh out;
  ASSERT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, 0.2 * h, &out).ok());
  EXPECT_EQ(out.stats.rejected_faces, 0);
  EXPECT_EQ(out.stats.regions_with_holes, 0);
  ASSERT_EQ(static_cast<int>(out.mesh.n_vertices()), (n + 1) * (n + 1));
  ASSERT_EQ(static_cast<int>(out.mesh.n_faces()), n * n);
  for (const auto f : out.mesh.faces()) EXPECT_EQ(out.mesh.valence(f), 4u);
  std::set<std::pair<long, long>> nodes;
  for (const auto v : out.mesh.vertices()) {
    const auto& p = out.mesh.point(v);
    const double i = p[0] / h, j = p[1] / h;
    EXPECT_NEAR(i, std::round(i), 1e-9);
    EXPECT_NEAR(j, std::round(j), 1e-9);
    EXPECT_NEAR(p[0], std::round(i) * h, 1e-9);
    EXPECT_NEAR(p[1], std::round(j) * h, 1e-9);
    nodes.insert({std::lround(i), std::lround(j)});
  }
  EXPECT_EQ(static_cast<int>(nodes.size()), (n + 1) * (n + 1));
  ExpectSimpleCounterClockwiseManifold(out.mesh);
  ExpectOriginsReproducePositions(s, out);
  const ExtractedMeshMetrics m = MeasureExtractedMesh(s, out, 30.0);
  EXPECT_EQ(m.quad_fraction, 1.0);
  EXPECT_EQ(m.n_corner_vertices, 4);
  EXPECT_NEAR(m.edge_min, h, 1e-9);
  EXPECT_NEAR(m.edge_max, h, 1e-9);
  EXPECT_LE(m.boundary_deviation_edges, 1e-12);
  EXPECT_EQ(m.planarity_max, 0.0);
}

TEST(QuadExtraction, FlatSquareLevelLinesThroughVerticesAndAlongEdges) {
  ExpectExactGrid(6, 1.0, 2.0);  // every level line along reference edges
  ExpectExactGrid(6, 1.0, 1.0);  // a level line through every vertex
}

TEST(QuadExtraction, FlatSquareLevelLinesBetweenVertices) {
  ExpectExactGrid(7, 6.0 / 7.0, 2.0);   // inner lines strictly between vertices, crossings on diagonals
  ExpectExactGrid(5, 0.9, 1.5);         // lines at 1.5, 3.0: between vertices, crossings inside triangles
}

TEST(QuadExtraction, RotatedGridOnDiskIsAManifoldDisk) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  for (const double angle : {0.3, 1.0}) {
    std::vector<double> phi, psi;
    RotatedCoordinates(s, angle, 2.0, 0.37, &phi, &psi);
    const auto [out, m] = ExtractValid(s, phi, psi, 0.4);
    std::cout << "disk, angle " << angle << ": " << m.n_vertices << " vertices, " << m.n_faces << " faces, quad fraction "
              << m.quad_fraction << ", min edge " << m.edge_min << ", boundary deviation (vertices) "
              << m.boundary_deviation_vertices << "\n";
    EXPECT_EQ(m.euler_characteristic, 1);
    EXPECT_EQ(m.boundary_loops, 1);
    EXPECT_TRUE(m.interior_non_quads.empty());
    EXPECT_GE(m.edge_min, 0.4);
    EXPECT_LE(m.boundary_deviation_vertices, 1e-9);
    EXPECT_EQ(m.planarity_max, 0.0);
    // Every cell within √2 h of the disk (radius 10, h = 2) is a face, none further out.
    EXPECT_GE(m.n_faces, M_PI * std::pow(10.0 - 2.0 * std::sqrt(2.0), 2) / 4.0);
    EXPECT_LE(m.n_faces, M_PI * std::pow(10.0 + 2.0 * std::sqrt(2.0), 2) / 4.0);
  }
}

// A grid at 40° to a square's sides: both families cross every side obliquely, so boundary
// cells alternate between triangles and pentagons. Moving the crossings just inside the
// boundary onto it must make the mesh more quad-dominant and keep it a simple manifold disk
// whose boundary vertices stay on the square.
TEST(QuadExtraction, ObliqueGridBoundaryTrianglesCollapse) {
  const SurfaceModel s(ScaledGrid(24, 1.0));
  std::vector<double> phi, psi;
  RotatedCoordinates(s, 40.0 * M_PI / 180.0, 2.3, 0.37, &phi, &psi);
  ExtractedMesh plain, paired;
  ASSERT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, 0.4, &plain, false).ok());
  ASSERT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, 0.4, &paired, true).ok());
  const ExtractedMeshMetrics before = MeasureExtractedMesh(s, plain, 30.0);
  const ExtractedMeshMetrics after = MeasureExtractedMesh(s, paired, 30.0);
  std::cout << "oblique square: quad fraction " << before.quad_fraction << " → " << after.quad_fraction << " ("
            << paired.stats.resplit_boundary_pairs << " pairs re-split, " << paired.stats.collapsed_boundary_triangles
            << " triangles collapsed)\n";
  EXPECT_GT(paired.stats.resplit_boundary_pairs + paired.stats.collapsed_boundary_triangles, 0);
  EXPECT_GT(after.quad_fraction, before.quad_fraction + 0.1);  // measured 0.677 → 0.803
  ExpectSimpleCounterClockwiseManifold(paired.mesh);
  ExpectOriginsReproducePositions(s, paired);
  EXPECT_EQ(after.euler_characteristic, 1);
  EXPECT_EQ(after.n_corner_vertices, 4);
  EXPECT_TRUE(after.interior_non_quads.empty());
  EXPECT_LE(after.boundary_deviation_edges, 1e-9);  // straight sides: boundary edges on them
  for (const auto v : paired.mesh.vertices())
    if (paired.mesh.is_boundary(v)) EXPECT_TRUE(paired.origin[v.idx()].on_boundary) << "vertex " << v.idx();
}

TEST(QuadExtraction, AnnulusHasTwoBoundaryLoops) {
  const SurfaceModel s(GeneratedMesh("annulus", 20.0, 8.0, 0.0, 0.7));
  std::vector<double> phi, psi;
  RotatedCoordinates(s, 0.5, 1.5, 0.21, &phi, &psi);
  const auto [out, m] = ExtractValid(s, phi, psi, 0.3);
  EXPECT_EQ(m.euler_characteristic, 0);
  EXPECT_EQ(m.boundary_loops, 2);
  EXPECT_TRUE(m.interior_non_quads.empty());
}

TEST(QuadExtraction, CurvedDomeOriginsReproducePositions) {
  const SurfaceModel s(GeneratedMesh("dome", 20.0, 16.0, 3.0, 0.8));
  std::vector<double> phi, psi;
  RotatedCoordinates(s, 0.2, 1.7, 0.1, &phi, &psi);
  ExtractedMesh out;
  ASSERT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, 0.2 * 1.7, &out).ok());
  EXPECT_EQ(out.stats.rejected_faces, 0);
  ExpectOriginsReproducePositions(s, out);
  const ExtractedMeshMetrics m = MeasureExtractedMesh(s, out, 30.0);
  EXPECT_EQ(m.euler_characteristic, 1);
  EXPECT_EQ(m.n_corner_vertices, 4);
  EXPECT_GT(m.planarity_max, 0.0);  // a curved surface: the quads are not planar
  EXPECT_TRUE(m.interior_non_quads.empty());
}

TEST(PlanarityDelta, KnownPolygons) {
  using V = Eigen::Vector3d;
  EXPECT_EQ(PlanarityDelta({V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}), 0.0);
  // Unit square with one corner lifted by z: diagonals (0,0,0)–(1,1,z) and (1,0,0)–(0,1,0).
  // Common normal of d1 = (1,1,z), d2 = (−1,1,0): n = (−z, −z, 2); distance
  // |(1,0,0)·n| / |n| = z / √(2z² + 4); mean diagonal (√(2 + z²) + √2) / 2.
  const double z = 0.3;
  const double expected = z / std::sqrt(2 * z * z + 4) / (0.5 * (std::sqrt(2 + z * z) + std::sqrt(2.0)));
  EXPECT_NEAR(PlanarityDelta({V(0, 0, 0), V(1, 0, 0), V(1, 1, z), V(0, 1, 0)}), expected, 1e-15);
  std::vector<V> hexagon;
  for (int k = 0; k < 6; ++k) hexagon.push_back(V(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0.0));
  EXPECT_NEAR(PlanarityDelta(hexagon), 0.0, 1e-15);
  hexagon[2].z() = 0.2;
  EXPECT_GT(PlanarityDelta(hexagon), 0.01);
  EXPECT_EQ(PlanarityDelta({V(0, 0, 0), V(1, 0, 3), V(0, 1, 7)}), 0.0);
}

TEST(QuadExtraction, RefusesMismatchedOrNonFiniteFields) {
  const SurfaceModel s(ScaledGrid(2, 1.0));
  ExtractedMesh out;
  EXPECT_FALSE(ExtractQuadMesh(s, {0.0}, {0.0}, 30.0, 0.1, &out).ok());
  std::vector<double> phi(s.num_vertices(), 0.5), psi(s.num_vertices(), 0.5);
  phi[3] = NAN;
  EXPECT_EQ(ExtractQuadMesh(s, phi, psi, 30.0, 0.1, &out).code(), StatusCode::kInvalidInput);
}

TEST(QuadExtraction, GreatCourtEndToEnd) {
  const double h = 3.0;
  const SurfaceModel s(GeneratedMesh("great_court", 0.0, 0.0, 0.0, 1.5));
  VertexConditions supports(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v)
    if (s.is_boundary(v)) supports[v] = BoundaryCondition::kFixed;
  MembraneSolution membrane;
  ASSERT_TRUE(SolveMembrane(s, supports, MembraneOptions(), 1350.0, &membrane).ok());
  GuidanceField guidance;
  ASSERT_TRUE(ComputeStrainGuidance(s, membrane.v_z, GuidanceOptions(), &guidance).ok());
  LevelSetSolution levelsets;
  ASSERT_TRUE(SolveLevelSets(s, guidance, LevelsetOptions(), h, &levelsets).ok());

  ExtractedMesh out;
  ASSERT_TRUE(ExtractQuadMesh(s, levelsets.phi, levelsets.psi, 30.0, 0.2 * h, &out).ok());
  const ExtractedMeshMetrics m = MeasureExtractedMesh(s, out, 30.0);
  std::cout << "Great Court: " << m.n_vertices << " vertices, " << m.n_faces << " faces, quad fraction "
            << m.quad_fraction << ", " << m.interior_non_quads.size() << " interior non-quads, corners "
            << m.n_corner_vertices << "/" << m.n_reference_corners << ", boundary deviation vertices "
            << m.boundary_deviation_vertices << " m, edges " << m.boundary_deviation_edges << " m, edge min/mean/max "
            << m.edge_min / h << "/" << m.edge_mean / h << "/" << m.edge_max / h << " h, δ max " << m.planarity_max
            << " mean " << m.planarity_mean << ", χ " << m.euler_characteristic << ", loops " << m.boundary_loops
            << ", collapsed " << out.stats.collapsed_edges << ", padded " << out.stats.padded_faces
            << ", holes " << out.stats.regions_with_holes << ", rejected " << out.stats.rejected_faces << "\n";
  std::cout << "faces by sides:";
  for (const auto& [sides, count] : m.face_sides) std::cout << " " << sides << ":" << count;
  std::cout << "\n";
  for (const auto& [sides, c] : m.interior_non_quads)
    std::cout << "  interior " << sides << "-gon at (" << c.x() << ", " << c.y() << ")\n";
  // The extraction's own guarantees.
  EXPECT_EQ(out.stats.rejected_faces, 0);
  EXPECT_EQ(out.stats.regions_with_holes, 0);
  EXPECT_EQ(m.euler_characteristic, 0);  // a disc with the Reading Room's hole
  EXPECT_EQ(m.boundary_loops, 2);
  ExpectOriginsReproducePositions(s, out);
  // Issue 5 acceptance, the parts that are the extraction's: every rectangle corner is a
  // mesh vertex, boundary vertices lie on the reference boundary, no edge below 0.2 h, and
  // away from the boundary the cells are quads except at the level sets' singular points
  // (where φ or ψ has a critical point or the two families fold: octagons, printed above).
  EXPECT_EQ(m.n_reference_corners, 4);
  EXPECT_EQ(m.n_corner_vertices, 4);
  EXPECT_LE(m.boundary_deviation_vertices, 0.01 * h);
  EXPECT_GE(m.edge_min, 0.2 * h);
  int interior_faces = 0;
  for (const auto f : out.mesh.faces()) {
    bool touches_boundary = false;
    for (const auto v : out.mesh.fv_range(f)) touches_boundary |= out.mesh.is_boundary(v);
    interior_faces += !touches_boundary;
  }
  // Measured: one interior octagon left (a concave cell at a singularity of the guidance,
  // (25.8, −19.8), that no cut into quads with angles ≥ 20° exists for); the others are cut.
  EXPECT_GE(out.stats.split_interior_polygons, 1);
  EXPECT_LE(m.interior_non_quads.size(), 2u);
  EXPECT_GE(1.0 - double(m.interior_non_quads.size()) / interior_faces, 0.995);
  // Issue 5: quad fraction ≥ 0.85 (measured 0.889 after boundary triangles are collapsed).
  EXPECT_GT(out.stats.collapsed_boundary_triangles, 0);
  EXPECT_GE(m.quad_fraction, 0.85);
  // ... and the boundary within 0.01 h of the reference, which along the Reading Room ring
  // (3 m chords stand up to 0.067 m off it) takes the stage's boundary refinement.
  EXPECT_GT(m.boundary_deviation_edges, 0.01 * h);
  const int quads_before = m.face_sides.at(4), faces_before = m.n_faces;
  const int inserted = RefineBoundaryChords(s, 0.01 * h, 0.25 * h, 0.2 * h, &out);
  const ExtractedMeshMetrics refined = MeasureExtractedMesh(s, out, 30.0);
  std::cout << "refined boundary: " << inserted << " vertices inserted, " << out.stats.slid_boundary_vertices
            << " slid; deviation " << m.boundary_deviation_edges << " → " << refined.boundary_deviation_edges
            << " m; quad fraction " << refined.quad_fraction << ", min edge " << refined.edge_min / h << " h\n";
  EXPECT_LE(refined.boundary_deviation_edges, 0.01 * h);
  EXPECT_EQ(refined.n_faces, faces_before + inserted);
  EXPECT_GE(refined.face_sides.at(4), quads_before);
  EXPECT_GE(refined.quad_fraction, 0.85);  // measured 0.863
  EXPECT_GE(refined.edge_min, 0.2 * h);
  EXPECT_EQ(refined.n_corner_vertices, 4);
  EXPECT_EQ(refined.euler_characteristic, 0);
  EXPECT_EQ(out.stats.rejected_faces, 0);
  ExpectOriginsReproducePositions(s, out);
}

}  // namespace
}  // namespace pqlayout

namespace pqlayout {
namespace {

using namespace extraction_test;

// φ, ψ with ties (values exactly on levels) or critical points, on the disk.
ExtractedMesh ExtractVariant(const SurfaceModel& s, int variant) {
  std::vector<double> phi, psi;
  RotatedCoordinates(s, 0.4, 2.0, 0.0, &phi, &psi);
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d p = s.position(v);
    if (variant == 0) {  // quarter levels: lines through vertices, along edges, over flat triangles
      phi[v] = std::round(4.0 * phi[v]) / 4.0;
      psi[v] = std::round(4.0 * psi[v]) / 4.0;
    } else if (variant == 1) {  // φ an integer at every vertex: a staircase of plateaus
      phi[v] = std::round(phi[v]);
      psi[v] = std::round(2.0 * psi[v]) / 2.0;
    } else {  // wavy: critical points of φ and ψ
      phi[v] += 0.9 * std::sin(0.5 * p.y());
      psi[v] += 0.9 * std::cos(0.45 * p.x());
    }
  }
  ExtractedMesh out;
  EXPECT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, 0.4, &out).ok());
  return out;
}

void ExpectManifoldDisk(const SurfaceModel& s, const ExtractedMesh& out) {
  const ExtractedMeshMetrics m = MeasureExtractedMesh(s, out, 30.0);
  EXPECT_EQ(out.stats.rejected_faces, 0);
  EXPECT_EQ(out.stats.regions_with_holes, 0);
  for (const auto v : out.mesh.vertices()) EXPECT_TRUE(out.mesh.is_manifold(v));
  EXPECT_EQ(m.euler_characteristic, 1);
  EXPECT_EQ(m.boundary_loops, 1);
  ExpectOriginsReproducePositions(s, out);
}

TEST(QuadExtraction, TiesAndCriticalPointsStayAManifoldDisk) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  for (const int variant : {0, 1, 2}) {
    SCOPED_TRACE(variant);
    ExpectManifoldDisk(s, ExtractVariant(s, variant));
  }
}

// Extracted on a coarse working mesh, the mesh is moved onto the fine reference afterwards. Round
// a hole the working boundary is a polygon inside the hole's circle, so a boundary vertex moves
// into the roof, towards the crossings (up to the chords' sagitta, 2²/(8·4) = 0.125 m here, as
// at the Great Court's Reading Room). Given the reference, the clean-up judges edges where they
// will lie: none is shorter than min_edge there. Without it, edges the collapses kept
// (≥ min_edge on the working mesh) end shorter on the reference on some of these grids.
TEST(QuadExtraction, ShortEdgesAreJudgedOnTheReference) {
  const SurfaceModel working(GeneratedMesh("annulus", 20.0, 8.0, 0.0, 2.0));
  const SurfaceModel reference(GeneratedMesh("annulus", 20.0, 8.0, 0.0, 0.25));
  const double h = 1.5, min_edge = 0.2 * h;
  const ClosestPointQuery& query = reference.closest_points();
  const auto shortest_on_reference = [&](const ExtractedMesh& e) {
    double shortest = INFINITY;
    for (const auto edge : e.mesh.edges()) {
      const auto he = e.mesh.halfedge_handle(edge, 0);
      const int a = e.mesh.from_vertex_handle(he).idx(), b = e.mesh.to_vertex_handle(he).idx();
      const Eigen::Vector3d pa = PlacedOnReference(query, e.origin[a], ToEigen(e.mesh.point(VertexHandle(a)))).point;
      const Eigen::Vector3d pb = PlacedOnReference(query, e.origin[b], ToEigen(e.mesh.point(VertexHandle(b)))).point;
      shortest = std::min(shortest, (pa - pb).norm());
    }
    return shortest;
  };
  int shortened = 0;
  for (const double angle : {0.2, 0.7, 1.1})
    for (int k = 0; k < 8; ++k) {
      std::vector<double> phi, psi;
      RotatedCoordinates(working, angle, h, 0.125 * k, &phi, &psi);
      ExtractedMesh judged, plain;
      ASSERT_TRUE(ExtractQuadMesh(working, phi, psi, 30.0, min_edge, &judged, true, {}, 0.0, &reference).ok());
      ASSERT_TRUE(ExtractQuadMesh(working, phi, psi, 30.0, min_edge, &plain).ok());
      EXPECT_GE(shortest_on_reference(judged), min_edge * (1.0 - 1e-12)) << "angle " << angle << ", offset " << k;
      for (const auto v : judged.mesh.vertices()) {  // already where OnReference puts them
        const Eigen::Vector3d p = ToEigen(judged.mesh.point(v));
        EXPECT_LE((PlacedOnReference(query, judged.origin[v.idx()], p).point - p).norm(), 1e-9);
      }
      if (shortest_on_reference(plain) < min_edge) ++shortened;
    }
  std::cout << "working-mesh extractions with an edge below min_edge on the reference, without it: " << shortened
            << " of 24\n";
  EXPECT_GT(shortened, 0);  // the case above is not vacuous
}

}  // namespace
}  // namespace pqlayout
