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
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::FlatGridSoup;
using testing::GeneratedMesh;
using testing::ToMesh;

// A flat grid of m × m squares of side `cell`, each split into two triangles.
TriMesh ScaledGrid(int m, double cell) {
  PolygonSoup soup = FlatGridSoup(m);
  for (auto& p : soup.points) p *= cell;
  return ToMesh(soup);
}

// φ, ψ = the coordinates rotated by `angle`, over h, plus offsets.
void RotatedCoordinates(const SurfaceModel& s, double angle, double h, double offset, std::vector<double>* phi,
                        std::vector<double>* psi) {
  phi->clear();
  psi->clear();
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d p = s.position(v);
    phi->push_back((std::cos(angle) * p.x() + std::sin(angle) * p.y()) / h + offset);
    psi->push_back((-std::sin(angle) * p.x() + std::cos(angle) * p.y()) / h + offset);
  }
}

Eigen::Vector3d OriginPosition(const SurfaceModel& s, const QuadMeshVertex& o) {
  const auto ids = s.face_vertices(o.face);
  return o.barycentric[0] * s.position(ids[0]) + o.barycentric[1] * s.position(ids[1]) +
         o.barycentric[2] * s.position(ids[2]);
}

void ExpectOriginsReproducePositions(const SurfaceModel& s, const ExtractedMesh& out) {
  ASSERT_EQ(out.origin.size(), out.mesh.n_vertices());
  for (const auto v : out.mesh.vertices()) {
    const QuadMeshVertex& o = out.origin[v.idx()];
    ASSERT_GE(o.face, 0);
    EXPECT_NEAR(o.barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(o.barycentric.minCoeff(), -1e-12);
    EXPECT_LE((OriginPosition(s, o) - ToEigen(out.mesh.point(v))).norm(), 1e-9) << "vertex " << v.idx();
  }
}

// Every face a simple polygon in the xy-plane (flat tests), counter-clockwise like the
// reference, every vertex manifold.
void ExpectSimpleCounterClockwiseManifold(const PolyMesh& mesh) {
  for (const auto f : mesh.faces()) {
    std::vector<Eigen::Vector2d> p;
    for (const auto v : mesh.fv_range(f)) p.push_back(ToEigen(mesh.point(v)).head<2>());
    const size_t n = p.size();
    double area = 0.0;
    for (size_t k = 0; k < n; ++k) area += p[k].x() * p[(k + 1) % n].y() - p[(k + 1) % n].x() * p[k].y();
    EXPECT_GT(area, 0.0) << "face " << f.idx();
    const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
    for (size_t a = 0; a < n; ++a)
      for (size_t b = a + 2; b < n; ++b) {
        if (a == 0 && b == n - 1) continue;  // adjacent through the wrap
        const Eigen::Vector2d p1 = p[a], p2 = p[(a + 1) % n], q1 = p[b], q2 = p[(b + 1) % n];
        const bool separated = cross(p2 - p1, q1 - p1) * cross(p2 - p1, q2 - p1) > 0 ||
                               cross(q2 - q1, p1 - q1) * cross(q2 - q1, p2 - q1) > 0;
        EXPECT_TRUE(separated) << "face " << f.idx() << " crosses itself";
      }
  }
  for (const auto v : mesh.vertices()) EXPECT_TRUE(mesh.is_manifold(v)) << "vertex " << v.idx();
}

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

struct ExtractionMetricsAndMesh {
  ExtractedMesh out;
  ExtractedMeshMetrics m;
};

// Extracts and checks what every extraction must give: no refused faces, no cells with holes,
// simple counter-clockwise faces on a manifold, origins that reproduce the positions.
ExtractionMetricsAndMesh ExtractValid(const SurfaceModel& s, const std::vector<double>& phi,
                                      const std::vector<double>& psi, double min_edge) {
  ExtractionMetricsAndMesh r;
  EXPECT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, min_edge, &r.out).ok());
  EXPECT_EQ(r.out.stats.rejected_faces, 0);
  EXPECT_EQ(r.out.stats.regions_with_holes, 0);
  ExpectSimpleCounterClockwiseManifold(r.out.mesh);
  ExpectOriginsReproducePositions(s, r.out);
  r.m = MeasureExtractedMesh(s, r.out, 30.0);
  return r;
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

// Faces with three consecutive vertices on the boundary (a panel with three points on the
// Reading Room ring, a horizontal circle, could only be planar lying flat).
int FacesWithThreeBoundaryVerticesInARow(const ExtractedMesh& out) {
  int count = 0;
  for (const auto f : out.mesh.faces()) {
    std::vector<bool> on;
    for (const auto v : out.mesh.fv_range(f)) on.push_back(out.origin[v.idx()].on_boundary);
    const size_t n = on.size();
    bool found = false;
    for (size_t k = 0; k < n; ++k) found |= on[k] && on[(k + 1) % n] && on[(k + 2) % n];
    count += found;
  }
  return count;
}

// A rotated grid on a disk of radius 10 with h = 2: boundary chords of up to ~2.8 m stand
// up to ~0.1 m off the circle. Refined to 0.01 h, the mesh must stay a simple manifold disk
// on the reference, gain exactly one face per inserted vertex, lose no quad, and never add a
// face with three boundary vertices in a row.
TEST(BoundaryRefinement, DiskChordsWithinToleranceAndStillAManifoldDisk) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  const double h = 2.0, tolerance = 0.01 * h;
  for (const double angle : {0.3, 1.0}) {
    std::vector<double> phi, psi;
    RotatedCoordinates(s, angle, h, 0.37, &phi, &psi);
    auto [out, before] = ExtractValid(s, phi, psi, 0.2 * h);
    ASSERT_GT(before.boundary_deviation_edges, 3.0 * tolerance);
    const int three_in_a_row = FacesWithThreeBoundaryVerticesInARow(out);
    const int inserted = RefineBoundaryChords(s, tolerance, 0.25 * h, 0.2 * h, &out);
    ExtractedMeshMetrics after = MeasureExtractedMesh(s, out, 30.0);
    std::cout << "disk, angle " << angle << ": deviation " << before.boundary_deviation_edges << " → "
              << after.boundary_deviation_edges << " m, " << inserted << " inserted, "
              << out.stats.slid_boundary_vertices << " slid, quad fraction " << before.quad_fraction << " → "
              << after.quad_fraction << "; faces with three boundary vertices in a row " << three_in_a_row << " → "
              << FacesWithThreeBoundaryVerticesInARow(out) << "\n";
    EXPECT_GT(inserted, 0);
    EXPECT_LE(after.boundary_deviation_edges, tolerance);
    EXPECT_EQ(after.n_faces, before.n_faces + inserted);
    EXPECT_GE(after.face_sides[4], before.face_sides[4]);
    EXPECT_EQ(after.euler_characteristic, 1);
    EXPECT_EQ(after.boundary_loops, 1);
    EXPECT_GE(after.edge_min, std::min(before.edge_min, 0.2 * h) - 1e-12);
    EXPECT_EQ(after.planarity_max, 0.0);
    EXPECT_LE(FacesWithThreeBoundaryVerticesInARow(out), three_in_a_row);  // none added
    ExpectSimpleCounterClockwiseManifold(out.mesh);
    ExpectOriginsReproducePositions(s, out);
    for (const auto v : out.mesh.vertices())
      if (out.mesh.is_boundary(v)) EXPECT_LE(ReferenceBoundary(s).Distance(ToEigen(out.mesh.point(v))), 1e-9);
  }
}

// Only a curved boundary is refined: on a square nothing moves and nothing is inserted, and
// tolerance 0 leaves a disk's mesh alone.
TEST(BoundaryRefinement, StraightBoundaryOrZeroToleranceChangesNothing) {
  const SurfaceModel square(ScaledGrid(24, 1.0));
  std::vector<double> phi, psi;
  RotatedCoordinates(square, 40.0 * M_PI / 180.0, 2.3, 0.37, &phi, &psi);
  auto [out, before] = ExtractValid(square, phi, psi, 0.4);
  EXPECT_EQ(RefineBoundaryChords(square, 1e-6, 0.5, 0.4, &out), 0);
  EXPECT_EQ(out.stats.slid_boundary_vertices, 0);
  EXPECT_EQ(MeasureExtractedMesh(square, out, 30.0).n_faces, before.n_faces);

  const SurfaceModel disk(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  RotatedCoordinates(disk, 0.3, 2.0, 0.37, &phi, &psi);
  auto [disk_out, disk_before] = ExtractValid(disk, phi, psi, 0.4);
  EXPECT_EQ(RefineBoundaryChords(disk, 0.0, 0.5, 0.4, &disk_out), 0);
  EXPECT_EQ(disk_out.stats.slid_boundary_vertices, 0);
  EXPECT_EQ(static_cast<int>(disk_out.mesh.n_faces()), disk_before.n_faces);
}

// A flat regular n-gon of circumradius r as a triangle mesh: a centre vertex and `rings`
// concentric copies of the polygon, each side cut into `cuts` pieces. Its boundary turns by
// 360°/n at each corner and not at all in between.
TriMesh PolygonDisk(int n, double r, int rings, int cuts) {
  PolygonSoup soup;
  soup.points.emplace_back(0.0, 0.0, 0.0);
  const int per_ring = n * cuts;
  for (int k = 1; k <= rings; ++k)
    for (int j = 0; j < per_ring; ++j) {
      const double a0 = 2.0 * M_PI * (j / cuts) / n, a1 = 2.0 * M_PI * (j / cuts + 1) / n;
      const double t = double(j % cuts) / cuts, scale = r * k / rings;
      soup.points.emplace_back(scale * ((1 - t) * std::cos(a0) + t * std::cos(a1)),
                               scale * ((1 - t) * std::sin(a0) + t * std::sin(a1)), 0.0);
    }
  const auto id = [&](int k, int j) { return k == 0 ? 0 : 1 + (k - 1) * per_ring + (j % per_ring); };
  for (int j = 0; j < per_ring; ++j) soup.faces.push_back({0, id(1, j), id(1, j + 1)});
  for (int k = 1; k < rings; ++k)
    for (int j = 0; j < per_ring; ++j) {
      soup.faces.push_back({id(k, j), id(k + 1, j), id(k + 1, j + 1)});
      soup.faces.push_back({id(k, j), id(k + 1, j + 1), id(k, j + 1)});
    }
  return ToMesh(soup);
}

// A span that starts a hair before a kink (a chord end located at the kink up to rounding)
// has that kink at offset ~0: FarthestKink must count it as the end and give the next kink.
TEST(BoundaryRefinement, FarthestKinkSkipsKinksAtTheSpansEnds) {
  const SurfaceModel s(PolygonDisk(24, 10.0, 4, 3));
  const ReferenceBoundary boundary(s);
  const double side = 2.0 * 10.0 * std::sin(M_PI / 24), min_turn = 5.0 * M_PI / 180.0, margin = 0.02;
  const Eigen::Vector3d corner(10.0, 0.0, 0.0);
  const auto at = boundary.Locate(corner);
  ASSERT_LE(at.distance, 1e-12);
  Eigen::Vector3d a, b;
  for (const double before : {0.0, 1e-13, 1e-6}) {
    const double from = at.arc - before;
    for (const double span : {before + 1.5 * side, before + 0.5 * side}) {
      boundary.PointAt(at.loop, from, &a);
      boundary.PointAt(at.loop, from + span, &b);
      const double kink = boundary.FarthestKink(a, b, at.loop, from, span, min_turn, margin);
      // The next corner if the span reaches it, else none.
      EXPECT_NEAR(kink, span > side ? before + side : -1.0, 1e-9) << before << " m before the corner, span " << span;
      // Without the margin, the corner itself would be the split point of the shorter span.
      if (before > 0.0 && span < side)
        EXPECT_NEAR(boundary.FarthestKink(a, b, at.loop, from, span, min_turn, 0.0), before, 1e-9);
    }
  }
  // A span that ends a hair past a kink, and nothing else: no kink.
  boundary.PointAt(at.loop, at.arc, &a);
  boundary.PointAt(at.loop, at.arc + side + 1e-9, &b);
  EXPECT_EQ(boundary.FarthestKink(a, b, at.loop, at.arc, side + 1e-9, min_turn, margin), -1.0);
}

// A polygonal boundary with sharp kinks (24-gon: 15°, sides 1.3 h): boundary vertices snap
// onto kinks and chords split at kinks. A kink at a chord's very end must count as that end:
// taken as a split point it gave zero-length edges, again and again (hole_offcentre × curvature
// inserted 1,312 vertices before the guard). Refined, every chord is within tolerance, no
// edge is shorter than the polygon's own sides allow, and at most one vertex per kink and
// per chord is inserted.
TEST(BoundaryRefinement, SharpKinksAtChordEndsInsertNoShortEdges) {
  const SurfaceModel s(PolygonDisk(24, 10.0, 8, 3));
  const double h = 2.0, tolerance = 0.01 * h;
  for (const double angle : {0.0, 0.3, 1.0}) {
    std::vector<double> phi, psi;
    RotatedCoordinates(s, angle, h, 0.37, &phi, &psi);
    auto [out, before] = ExtractValid(s, phi, psi, 0.2 * h);
    ASSERT_GT(before.boundary_deviation_edges, 3.0 * tolerance);
    const int inserted = RefineBoundaryChords(s, tolerance, 0.25 * h, 0.2 * h, &out);
    const ExtractedMeshMetrics after = MeasureExtractedMesh(s, out, 30.0);
    std::cout << "24-gon, angle " << angle << ": deviation " << before.boundary_deviation_edges << " → "
              << after.boundary_deviation_edges << " m, " << inserted << " inserted, "
              << out.stats.slid_boundary_vertices << " slid, min edge " << before.edge_min / h << " → "
              << after.edge_min / h << " h, quad fraction " << before.quad_fraction << " → " << after.quad_fraction
              << "\n";
    EXPECT_LE(after.boundary_deviation_edges, tolerance);
    EXPECT_LE(inserted, 24);
    EXPECT_EQ(after.n_faces, before.n_faces + inserted);
    EXPECT_GE(after.face_sides.at(4), before.face_sides.at(4));
    EXPECT_GE(after.edge_min, std::min(before.edge_min, 0.1 * h));
    EXPECT_EQ(after.euler_characteristic, 1);
    EXPECT_EQ(after.boundary_loops, 1);
    ExpectSimpleCounterClockwiseManifold(out.mesh);
    ExpectOriginsReproducePositions(s, out);
  }
}

}  // namespace
}  // namespace pqlayout

namespace pqlayout {
namespace {

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

}  // namespace
}  // namespace pqlayout
