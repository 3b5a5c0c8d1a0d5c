// Boundary refinement (geometry/boundary_refinement.h, geometry/reference_boundary.h): chords
// kept within a tolerance of a curved or polygonal reference boundary, on flat discs and
// polygons with straight level lines, where every answer can be checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "geometry/boundary_refinement.h"
#include "geometry/boundary_slides.h"
#include "geometry/reference_boundary.h"
#include "tests/extraction_test_helpers.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::GeneratedMesh;
using namespace extraction_test;

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

// How far the chord a – b strays from the reference boundary between its ends (one loop, the
// shorter way round).
double ChordOff(const ReferenceBoundary& boundary, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const auto la = boundary.Locate(a), lb = boundary.Locate(b);
  const double length = boundary.length(0), span = std::fmod(lb.arc - la.arc + length, length);
  return span < 0.5 * length ? boundary.ChordDeviation(a, b, 0, la.arc, span)
                             : boundary.ChordDeviation(b, a, 0, lb.arc, length - span);
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

// The arc lengths of the mesh's boundary vertices along the disk's one boundary loop, sorted.
std::vector<double> BoundaryArcs(const ReferenceBoundary& boundary, const ExtractedMesh& out) {
  std::vector<double> arcs;
  for (const auto v : out.mesh.vertices())
    if (out.mesh.is_boundary(v)) arcs.push_back(boundary.Locate(ToEigen(out.mesh.point(v))).arc);
  std::sort(arcs.begin(), arcs.end());
  return arcs;
}

// Largest chord deviation of the boundary from arc `from` forward by `span`, cut into k
// equal pieces.
double EqualPiecesDeviation(const ReferenceBoundary& boundary, double from, double span, int k) {
  double deviation = 0.0;
  for (int j = 0; j < k; ++j) {
    Eigen::Vector3d p, q;
    boundary.PointAt(0, from + j * span / k, &p);
    boundary.PointAt(0, from + (j + 1) * span / k, &q);
    deviation = std::max(deviation, boundary.ChordDeviation(p, q, 0, from + j * span / k, span / k));
  }
  return deviation;
}

// Without slides, each chord beyond tolerance is cut into equal pieces, as few as follow the
// boundary: one piece fewer would not. Halving (before 2026-12-03) cut a chord that needs
// three pieces into four, one vertex and one boundary triangle more, and its pieces below
// min_edge on the corpus' small openings.
TEST(BoundaryRefinement, ChordsCutIntoTheFewestEqualPieces) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  const ReferenceBoundary boundary(s);
  const double h = 2.0, tolerance = 0.01 * h, length = boundary.length(0);
  int three_or_more = 0;
  for (const double angle : {0.3, 1.0}) {
    std::vector<double> phi, psi;
    RotatedCoordinates(s, angle, h, 0.37, &phi, &psi);
    auto [out, before] = ExtractValid(s, phi, psi, 0.2 * h);
    const std::vector<double> ends = BoundaryArcs(boundary, out);
    const int inserted = RefineBoundaryChords(s, tolerance, 0.0, 0.2 * h, &out);
    const std::vector<double> after = BoundaryArcs(boundary, out);
    ASSERT_EQ(after.size(), ends.size() + inserted);
    for (size_t i = 0; i < ends.size(); ++i) {
      const double from = ends[i], forward = std::fmod(ends[(i + 1) % ends.size()] - from + length, length);
      std::vector<double> inside;  // the inserted vertices' offsets along this chord
      for (const double a : after) {
        const double offset = std::fmod(a - from + length, length);
        if (offset > 1e-9 && offset < forward - 1e-9) inside.push_back(offset);
      }
      std::sort(inside.begin(), inside.end());
      const int k = static_cast<int>(inside.size()) + 1;
      for (int j = 1; j < k; ++j) EXPECT_NEAR(inside[j - 1], j * forward / k, 1e-6 * forward) << "chord " << i;
      EXPECT_LE(EqualPiecesDeviation(boundary, from, forward, k), tolerance + 1e-12) << "chord " << i;
      if (k > 1) EXPECT_GT(EqualPiecesDeviation(boundary, from, forward, k - 1), tolerance) << "chord " << i;
      three_or_more += k >= 3;
    }
  }
  EXPECT_GT(three_or_more, 0);  // the case halving got wrong is there
}

// A crossing X just inside the boundary, next to where the chord A → B is cut (the two
// openings × curvature roof: a diagonal 0.09 h long from the new boundary point to such a
// crossing): X moves onto that point instead (MoveOntoBoundary). Flat disk of radius 10, A and
// B its boundary vertices nearest ±8° (the chord stands ~0.1 m off, > 0.04; halves are within),
// X at radius 9.5 on the bisector, 0.5 from the cut point, min_edge 0.8; four faces round X.
// With X at radius 9 (1 m from the point) a vertex is inserted as before.
TEST(BoundaryRefinement, ACrossingNextToANewBoundaryPointMovesOntoIt) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  const double tolerance = 0.04, min_edge = 0.8;
  const auto nearest = [&](double degrees) {
    int best = -1;
    for (int v = 0; v < s.num_vertices(); ++v) {
      if (!s.is_boundary(v)) continue;
      const Eigen::Vector3d p = s.position(v);
      const double off = std::abs(std::atan2(p.y(), p.x()) - degrees * M_PI / 180.0);
      if (best < 0 || off < std::abs(std::atan2(s.position(best).y(), s.position(best).x()) - degrees * M_PI / 180.0))
        best = v;
    }
    return s.position(best);
  };
  for (const double x_radius : {9.5, 9.0}) {
    // A, B, X, D, C: faces [A, B, X], [B, D, X], [X, D, C], [A, X, C].
    const std::vector<Eigen::Vector3d> position = {nearest(-8.0), nearest(8.0), Eigen::Vector3d(x_radius, 0.0, 0.0),
                                                   Eigen::Vector3d(8.0, 1.5, 0.0), Eigen::Vector3d(8.0, -1.5, 0.0)};
    ExtractedMesh out;
    out.mesh = BuildPolyMesh(position, {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {0, 2, 4}}, &out.stats.rejected_faces);
    out.origin.resize(5);
    out.origin[0].on_boundary = out.origin[1].on_boundary = true;
    const int inserted = RefineBoundaryChords(s, tolerance, 0.0, min_edge, &out);
    const ExtractedMeshMetrics after = MeasureExtractedMesh(s, out, 30.0);
    EXPECT_EQ(out.stats.rejected_faces, 0);
    ExpectSimpleCounterClockwiseManifold(out.mesh);
    if (x_radius == 9.5) {
      EXPECT_EQ(inserted, 0);
      EXPECT_EQ(out.stats.moved_onto_boundary, 1);
      EXPECT_EQ(out.mesh.n_vertices(), 5u);
      EXPECT_EQ(out.mesh.n_faces(), 3u);  // [A, B, X] flattened and gone
      EXPECT_TRUE(out.origin[2].on_boundary);
      EXPECT_NEAR(ToEigen(out.mesh.point(VertexHandle(2))).norm(), 10.0, 0.01);
      EXPECT_GE(after.edge_min, 1.0);
    } else {
      EXPECT_EQ(inserted, 1);
      EXPECT_EQ(out.stats.moved_onto_boundary, 0);
      EXPECT_EQ(out.mesh.n_faces(), 5u);
    }
  }
}

// The boundary vertex of the radius-10 disk nearest the rim point at `degrees`.
Eigen::Vector3d NearestOnRim(const SurfaceModel& s, double degrees) {
  const Eigen::Vector3d target(10.0 * std::cos(degrees * M_PI / 180.0), 10.0 * std::sin(degrees * M_PI / 180.0), 0.0);
  int best = -1;
  for (int v = 0; v < s.num_vertices(); ++v)
    if (s.is_boundary(v) && (best < 0 || (s.position(v) - target).norm() < (s.position(best) - target).norm())) best = v;
  return s.position(best);
}

// A chord just beyond tolerance on a quad cell, whose halves would be shorter than min_edge:
// instead of a vertex (a triangle more and two short edges) one end slides until the chord is
// within tolerance (ShortenChord). Flat disk of radius 10, A and B its boundary vertices nearest
// ±5.4° (measured: ±6°, chord 2.09 m, 0.055 off its polygonal arc; tolerance 0.04), the quad
// [A, B, D, C] with D, C at radius 8; min_edge 1.2 (halves 1.05), slides up to 0.5: the
// chord is shortened to 1.80 m, exactly within tolerance, by one slide. With
// min_edge 0.5 the chord is cut.
TEST(BoundaryRefinement, AChordWithTooShortPiecesOnAQuadIsShortenedInstead) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  const ReferenceBoundary boundary(s);
  const double tolerance = 0.04;
  const auto nearest = [&](double degrees) { return NearestOnRim(s, degrees); };
  const auto deviation = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return ChordOff(boundary, a, b); };
  for (const double min_edge : {1.2, 0.5}) {
    const std::vector<Eigen::Vector3d> position = {nearest(-5.4), nearest(5.4), Eigen::Vector3d(8.0, 1.0, 0.0),
                                                   Eigen::Vector3d(8.0, -1.0, 0.0)};
    ASSERT_GT(deviation(position[0], position[1]), tolerance);
    ExtractedMesh out;
    out.mesh = BuildPolyMesh(position, {{0, 1, 2, 3}}, &out.stats.rejected_faces);
    out.origin.resize(4);
    out.origin[0].on_boundary = out.origin[1].on_boundary = true;
    const int inserted = RefineBoundaryChords(s, tolerance, 0.5, min_edge, &out);
    const Eigen::Vector3d a = ToEigen(out.mesh.point(VertexHandle(0))), b = ToEigen(out.mesh.point(VertexHandle(1)));
    std::cout << "min_edge " << min_edge << ": " << inserted << " inserted, " << out.stats.slid_boundary_vertices
              << " slid, chord " << (a - b).norm() << " m, " << deviation(a, b) << " off\n";
    if (min_edge > 1.0) {
      EXPECT_EQ(inserted, 0);
      EXPECT_EQ(out.stats.slid_boundary_vertices, 1);
      EXPECT_EQ(out.mesh.n_faces(), 1u);
      EXPECT_LE(deviation(a, b), tolerance + 1e-9);
      EXPECT_LE(boundary.Distance(a) + boundary.Distance(b), 1e-9);
      EXPECT_GT((a - b).norm(), 1.7);  // shortened by little
    } else {
      EXPECT_EQ(inserted, 1);
      EXPECT_EQ(out.mesh.n_faces(), 2u);
    }
  }
}

// The same chord on a pentagon, whose halves would be shorter than min_edge: there the new
// vertex makes two quads of the cell, so it is cut, but its ends first move apart along the
// boundary until the halves are min_edge long (WidenChord; the two openings × curvature roof: a
// 0.38 h chord cut into two 0.19 h edges). Flat disk of radius 10, A and B its boundary
// vertices nearest ±5.4° (measured: ±6°, chord 2.09 m, beyond tolerance 0.04; halves within),
// the pentagon [A, B, D, E, C]; min_edge 1.1: both ends slide ~0.075 m, the halves are ≥ 1.1 m,
// two quads. Without room to slide (max_slide 0) the halves stay 1.045 m, as before. With A or
// B a corner (pinned), the other slides alone, twice as far.
TEST(BoundaryRefinement, AShortChordOnAPentagonIsWidenedBeforeItIsCut) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  const double tolerance = 0.04, min_edge = 1.1;
  const auto nearest = [&](double degrees) { return NearestOnRim(s, degrees); };
  for (const auto& [max_slide, corner] : {std::pair{0.5, -1}, {0.0, -1}, {0.5, 0}, {0.5, 1}}) {
    const std::vector<Eigen::Vector3d> position = {nearest(-5.4), nearest(5.4), Eigen::Vector3d(8.0, 1.0, 0.0),
                                                   Eigen::Vector3d(7.5, 0.0, 0.0), Eigen::Vector3d(8.0, -1.0, 0.0)};
    const double chord = (position[0] - position[1]).norm();
    ASSERT_GT(chord, 1.8);
    ASSERT_LT(chord, 2.0 * min_edge);
    ExtractedMesh out;
    out.mesh = BuildPolyMesh(position, {{0, 1, 2, 3, 4}}, &out.stats.rejected_faces);
    out.origin.resize(5);
    out.origin[0].on_boundary = out.origin[1].on_boundary = true;
    if (corner >= 0) out.origin[corner].corner = true;
    const int inserted = RefineBoundaryChords(s, tolerance, max_slide, min_edge, &out);
    const ExtractedMeshMetrics after = MeasureExtractedMesh(s, out, 30.0);
    EXPECT_EQ(inserted, 1);
    ASSERT_EQ(out.mesh.n_faces(), 2u);
    for (const auto f : out.mesh.faces()) EXPECT_EQ(out.mesh.valence(f), 4u);
    ExpectSimpleCounterClockwiseManifold(out.mesh);
    const Eigen::Vector3d a = ToEigen(out.mesh.point(VertexHandle(0))), b = ToEigen(out.mesh.point(VertexHandle(1)));
    const Eigen::Vector3d m = ToEigen(out.mesh.point(VertexHandle(5)));  // the new vertex
    const ReferenceBoundary boundary(s);
    EXPECT_LE(ChordOff(boundary, a, m), tolerance + 1e-9);
    EXPECT_LE(ChordOff(boundary, m, b), tolerance + 1e-9);
    EXPECT_GT(ChordOff(boundary, a, b), tolerance);  // the widened chord still needed its vertex
    if (max_slide > 0.0) {
      EXPECT_EQ(out.stats.slid_boundary_vertices, corner >= 0 ? 1 : 2);
      EXPECT_GE(after.edge_min, min_edge);
      EXPECT_NEAR((a - b).norm(), 2.0 * boundary_internal::kRoomFactor * min_edge, 0.01);
      EXPECT_NEAR(a.norm(), 10.0, 0.01);
      EXPECT_NEAR(b.norm(), 10.0, 0.01);
      if (corner == 0) EXPECT_EQ(a, position[0]);  // pinned: the other end took its share
      if (corner == 1) EXPECT_EQ(b, position[1]);
      if (corner < 0) EXPECT_NEAR(a.y(), -b.y(), 1e-6);  // both moved alike
    } else {
      EXPECT_EQ(out.stats.slid_boundary_vertices, 0);
      EXPECT_NEAR(after.edge_min, 0.5 * chord, 0.01);
    }
  }
}

// All or none: the pentagon above with A's neighbour C on the rim 0.03 m beyond it, in the quad
// [C, A, X, Y] next door. B slides first; A cannot follow (it would pass C: the quad's corner
// turns inside out), so B goes back where it was and nothing has moved.
TEST(BoundaryRefinement, AWidenedChordMovesBothEndsOrNeither) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  const double tolerance = 0.04, min_edge = 1.1;
  const Eigen::Vector3d a = NearestOnRim(s, -5.4), b = NearestOnRim(s, 5.4), beyond = NearestOnRim(s, -10.0);
  // A, B, D, E, X, C, Y
  const std::vector<Eigen::Vector3d> position = {a, b, Eigen::Vector3d(8.0, 1.0, 0.0), Eigen::Vector3d(7.5, 0.0, 0.0),
                                                 Eigen::Vector3d(8.5, -1.5, 0.0), a + 0.03 * (beyond - a).normalized(),
                                                 Eigen::Vector3d(8.0, -2.6, 0.0)};
  ExtractedMesh out;
  out.mesh = BuildPolyMesh(position, {{0, 1, 2, 3, 4}, {5, 0, 4, 6}}, &out.stats.rejected_faces);
  ASSERT_EQ(out.mesh.n_faces(), 2u);
  out.origin.resize(7);
  out.origin[0].on_boundary = out.origin[1].on_boundary = out.origin[5].on_boundary = true;
  RefineBoundaryChords(s, tolerance, 0.5, min_edge, &out);
  EXPECT_EQ(out.stats.slid_boundary_vertices, 0);
  EXPECT_EQ(ToEigen(out.mesh.point(VertexHandle(0))), a);
  EXPECT_EQ(ToEigen(out.mesh.point(VertexHandle(1))), b);
  EXPECT_EQ(out.stats.rejected_faces, 0);
  ExpectSimpleCounterClockwiseManifold(out.mesh);
}

}  // namespace
}  // namespace pqlayout

namespace pqlayout {
namespace {

// A corner left off the reference boundary (CGAL had moved working-mesh corners 0.35 m into a
// steep dome, geometry/remesh.cc): its chords stay that far off however they are cut, so they
// are left alone — they were split until the insertion guard, 268 vertices, edges of 1e-10 h.
TEST(BoundaryRefinement, AChordEndOffTheBoundaryIsNotSplitWithoutEnd) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
  const double h = 2.0, tolerance = 0.01 * h;
  std::vector<double> phi, psi;
  RotatedCoordinates(s, 0.3, h, 0.37, &phi, &psi);
  auto [reference_out, before] = ExtractValid(s, phi, psi, 0.2 * h);
  ExtractedMesh out = reference_out;
  const int inserted_on_boundary = RefineBoundaryChords(s, tolerance, 0.25 * h, 0.2 * h, &reference_out);
  int off = -1;
  for (const auto v : out.mesh.vertices())
    if (out.origin[v.idx()].on_boundary && !out.origin[v.idx()].corner) off = v.idx();
  ASSERT_GE(off, 0);
  out.origin[off].corner = true;  // never slid
  const VertexHandle vh(off);
  out.mesh.set_point(vh, out.mesh.point(vh) * (1.0 - 0.3 / out.mesh.point(vh).norm()));  // 0.3 m towards the centre
  const int inserted = RefineBoundaryChords(s, tolerance, 0.25 * h, 0.2 * h, &out);
  EXPECT_LE(inserted, inserted_on_boundary + 2);
  EXPECT_GE(MeasureExtractedMesh(s, out, 30.0).edge_min, 0.1 * h);
}

}  // namespace
}  // namespace pqlayout
