// Quad extraction across seams (geometry/quad_extraction.h with geometry/seams.h) on
// analytic fields: a radial grid on a flat annulus whose angle function jumps by N levels
// across the seam, the branch point of φ + iψ = c·z^{3/2} at a seam tip, and a seam across
// which nothing jumps (must give exactly the seam-free mesh).
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <iostream>
#include <set>

#include "geometry/quad_extraction.h"
#include "geometry/seams.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::ClosestInterior;
using testing::GeneratedMesh;

// The polar angle about `centre` of every vertex of the cut surface, continuous over the cut
// surface (it is simply connected, so the angle has a single-valued branch there): starts
// at `start` with its atan2 value and moves by less than π along every edge. A vertex at the
// centre (a seam tip) gets 0 and is not passed through.
std::vector<double> UnwrappedAngle(const SurfaceModel& cut, const Eigen::Vector2d& centre, int start) {
  const TriMesh& mesh = cut.mesh();
  const auto raw = [&](int v) {
    const Eigen::Vector2d d = cut.position(v).head<2>() - centre;
    return std::atan2(d.y(), d.x());
  };
  const auto at_centre = [&](int v) { return (cut.position(v).head<2>() - centre).norm() < 1e-12; };
  std::vector<double> theta(cut.num_vertices(), NAN);
  theta[start] = raw(start);
  std::deque<int> queue{start};
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop_front();
    for (const auto w : mesh.vv_range(VertexHandle(v))) {
      if (!std::isnan(theta[w.idx()]) || at_centre(w.idx())) continue;
      const double base = raw(w.idx());
      theta[w.idx()] = base + 2.0 * M_PI * std::round((theta[v] - base) / (2.0 * M_PI));
      queue.push_back(w.idx());
    }
  }
  for (int v = 0; v < cut.num_vertices(); ++v) {
    if (at_centre(v)) theta[v] = 0.0;
    EXPECT_FALSE(std::isnan(theta[v])) << "vertex " << v << " not reached";
  }
  return theta;
}

// The offset u₊ − s·u₋ that the values have across path p (the same for every copy pair).
int MeasuredOffset(const SeamCut& cut, int path, int sign, const std::vector<double>& u) {
  int offset = 0;
  bool first = true;
  for (const SeamCopyPair& pair : cut.copy_pairs()) {
    if (pair.path != path || pair.minus == pair.plus) continue;
    const double jump = u[pair.plus] - sign * u[pair.minus];
    if (first) offset = static_cast<int>(std::lround(jump)), first = false;
    EXPECT_NEAR(jump, offset, 1e-9) << "vertex " << pair.original_vertex;
  }
  return offset;
}

void ExpectManifoldWithOrigins(const SurfaceModel& s, const ExtractedMesh& out) {
  EXPECT_EQ(out.stats.rejected_faces, 0);
  EXPECT_EQ(out.stats.regions_with_holes, 0);
  EXPECT_EQ(out.stats.unmatched_seam_edges, 0);
  for (const auto v : out.mesh.vertices()) EXPECT_TRUE(out.mesh.is_manifold(v)) << "vertex " << v.idx();
  ASSERT_EQ(out.origin.size(), out.mesh.n_vertices());
  for (const auto v : out.mesh.vertices()) {
    const QuadMeshVertex& o = out.origin[v.idx()];
    ASSERT_GE(o.face, 0);
    const auto ids = s.face_vertices(o.face);
    const Eigen::Vector3d p =
        o.barycentric[0] * s.position(ids[0]) + o.barycentric[1] * s.position(ids[1]) + o.barycentric[2] * s.position(ids[2]);
    EXPECT_NEAR(o.barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(o.barycentric.minCoeff(), -1e-12);
    EXPECT_LE((p - ToEigen(out.mesh.point(v))).norm(), 1e-9) << "vertex " << v.idx();
    // Seam vertices are no boundary: only vertices on the mesh boundary are on the reference boundary.
    EXPECT_EQ(o.on_boundary, out.mesh.is_boundary(v)) << "vertex " << v.idx();
  }
  // Flat tests: every face counter-clockwise in the xy-plane, no two faces on the same
  // vertices, and the faces cover the reference once (its area up to the boundary chords):
  // no fold or double cover across a seam.
  double total = 0.0;
  std::set<std::set<int>> vertex_sets;
  for (const auto f : out.mesh.faces()) {
    std::vector<Eigen::Vector2d> q;
    std::set<int> ids;
    for (const auto v : out.mesh.fv_range(f)) q.push_back(ToEigen(out.mesh.point(v)).head<2>()), ids.insert(v.idx());
    double area = 0.0;
    for (size_t k = 0; k < q.size(); ++k) area += q[k].x() * q[(k + 1) % q.size()].y() - q[(k + 1) % q.size()].x() * q[k].y();
    EXPECT_GT(area, 0.0) << "face " << f.idx();
    EXPECT_TRUE(vertex_sets.insert(ids).second) << "face " << f.idx() << " repeated";
    total += area / 2.0;
  }
  EXPECT_NEAR(total, s.total_area(), 0.03 * s.total_area());
}

// The annulus r ∈ [4, 10] (reference edge `edge`) cut open along one seam.
struct CutAnnulus {
  std::unique_ptr<SurfaceModel> surface;
  std::vector<std::vector<int>> paths;
  std::unique_ptr<SeamCut> seam_cut;
};
CutAnnulus MakeCutAnnulus(double edge) {
  CutAnnulus a;
  a.surface = std::make_unique<SurfaceModel>(GeneratedMesh("annulus", 20.0, 8.0, 0.0, edge));
  a.paths = RouteSeams(*a.surface, std::vector<double>(a.surface->num_faces(), 1.0), {});
  EXPECT_EQ(a.paths.size(), 1u);
  EXPECT_TRUE(SeamCut::Build(*a.surface, a.paths, &a.seam_cut).ok());
  return a;
}

// Annulus r ∈ [4, 10] cut along one seam; φ = N θ / 2π with θ continuous on the cut surface
// (so φ jumps by N across the seam: sign +1, offset ±N), ψ = r − ½ (no jump): N radial lines
// and the circles r = 4.5 … 9.5 between the two boundary circles. Every cell a quad, none
// split at the seam: N · 8 vertices, N · 7 faces, χ = 0.
TEST(SeamExtraction, AnnulusRadialGridIsSeamless) {
  const CutAnnulus annulus = MakeCutAnnulus(0.5);
  const SurfaceModel& s = *annulus.surface;
  const auto& paths = annulus.paths;
  const auto& seam_cut = annulus.seam_cut;
  const SurfaceModel& cut = seam_cut->cut();
  const int n = 24;
  const int middle = paths[0][paths[0].size() / 2];
  const double theta_seam = std::atan2(s.position(middle).y(), s.position(middle).x());
  int start = -1;
  for (const auto& pair : seam_cut->copy_pairs())
    if (pair.original_vertex == middle) start = pair.minus;
  ASSERT_GE(start, 0);
  const std::vector<double> theta = UnwrappedAngle(cut, Eigen::Vector2d::Zero(), start);
  for (const double phase : {0.0, 0.5, 0.3}) {  // φ = 0 along the seam (ties at seam vertices), or off it
    SCOPED_TRACE(phase);
    std::vector<double> phi(cut.num_vertices()), psi(cut.num_vertices());
    for (int v = 0; v < cut.num_vertices(); ++v) {
      phi[v] = n * (theta[v] - theta_seam) / (2.0 * M_PI) + phase;
      psi[v] = cut.position(v).head<2>().norm() - 0.5;
    }
    SeamTransitions transitions{seam_cut.get(), {1}, {MeasuredOffset(*seam_cut, 0, 1, phi)}, {0}};
    EXPECT_EQ(std::abs(transitions.phi_offset[0]), n);
    EXPECT_EQ(MeasuredOffset(*seam_cut, 0, 1, psi), 0);
    ExtractedMesh out;
    ASSERT_TRUE(ExtractQuadMesh(s, transitions, phi, psi, 30.0, 0.2, &out).ok());
    ExpectManifoldWithOrigins(s, out);
    const ExtractedMeshMetrics m = MeasureExtractedMesh(s, out, 30.0);
    std::cout << "annulus, N = " << n << ", phase " << phase << ": " << m.n_vertices << " vertices, " << m.n_faces
              << " faces, quad fraction " << m.quad_fraction << ", χ = " << m.euler_characteristic
              << ", transition mismatch " << out.stats.seam_transition_mismatch << "\n";
    EXPECT_EQ(m.n_vertices, n * 8);
    EXPECT_EQ(m.n_faces, n * 7);
    EXPECT_EQ(m.n_edges, n * 15);
    EXPECT_EQ(m.quad_fraction, 1.0);
    EXPECT_EQ(m.euler_characteristic, 0);
    EXPECT_EQ(m.boundary_loops, 2);
    EXPECT_EQ(m.vertex_valence.at(4), n * 6);
    EXPECT_EQ(m.vertex_valence.at(3), n * 2);
    EXPECT_LE(out.stats.seam_transition_mismatch, 1e-12);
    // Every vertex on a radial line k and a circle: each (k, circle) once.
    std::set<std::pair<int, int>> nodes;
    for (const auto v : out.mesh.vertices()) {
      const Eigen::Vector3d p = ToEigen(out.mesh.point(v));
      const double k = (std::atan2(p.y(), p.x()) - theta_seam) * n / (2.0 * M_PI) + phase;
      const double ring = (p.head<2>().norm() - 4.0) * 2.0;  // 0, 1 (r = 4.5), 3 (5.5), …, 11 (9.5), 12 (r = 10)
      EXPECT_NEAR(k, std::round(k), 0.02) << "vertex " << v.idx();
      EXPECT_NEAR(ring, std::round(ring), 0.05) << "vertex " << v.idx();
      nodes.insert({static_cast<int>(((std::lround(k) % n) + n) % n), static_cast<int>(std::lround(ring))});
    }
    EXPECT_EQ(static_cast<int>(nodes.size()), n * 8);

    // The test can fail: the same values on the cut surface without identification split
    // every cell on the seam (a disc, χ = 1, extra vertices where the curves meet the slit).
    ExtractedMesh slit;
    ASSERT_TRUE(ExtractQuadMesh(cut, phi, psi, 30.0, 0.2, &slit).ok());
    const ExtractedMeshMetrics ms = MeasureExtractedMesh(cut, slit, 30.0);
    EXPECT_EQ(ms.euler_characteristic, 1);
    EXPECT_GE(ms.n_vertices, n * 8 + 12);
  }
}

// Both families jump: φ = N θ / 2π (offset ±N) and ψ = r − 0.3 + M θ / 2π (offset ±M), so
// the ψ lines are spirals that run from the inner to the outer boundary. Without collapses
// or boundary fixes the mesh is exactly the arrangement of the curves: on every radial line
// k the 6 levels of ψ strictly inside plus its two ends, plus the ends of the M spirals
// that meet each boundary circle; every interior vertex a crossing of valence 4, every
// interior cell a quad.
TEST(SeamExtraction, AnnulusSpiralGridJumpsInBothFamilies) {
  const CutAnnulus annulus = MakeCutAnnulus(0.5);
  const SurfaceModel& s = *annulus.surface;
  const auto& seam_cut = annulus.seam_cut;
  const SurfaceModel& cut = seam_cut->cut();
  const int n = 24, spiral = 3;
  const std::vector<double> theta = UnwrappedAngle(cut, Eigen::Vector2d::Zero(), seam_cut->copy_pairs()[0].minus);
  std::vector<double> phi(cut.num_vertices()), psi(cut.num_vertices());
  for (int v = 0; v < cut.num_vertices(); ++v) {
    phi[v] = n * theta[v] / (2.0 * M_PI);
    psi[v] = cut.position(v).head<2>().norm() - 0.3 + spiral * theta[v] / (2.0 * M_PI);
  }
  const SeamTransitions transitions{seam_cut.get(), {1}, {MeasuredOffset(*seam_cut, 0, 1, phi)},
                                    {MeasuredOffset(*seam_cut, 0, 1, psi)}};
  EXPECT_EQ(std::abs(transitions.phi_offset[0]), n);
  EXPECT_EQ(std::abs(transitions.psi_offset[0]), spiral);
  ExtractedMesh out;
  ASSERT_TRUE(ExtractQuadMesh(s, transitions, phi, psi, 30.0, 0.0, &out, false).ok());
  ExpectManifoldWithOrigins(s, out);
  const ExtractedMeshMetrics m = MeasureExtractedMesh(s, out, 30.0);
  std::cout << "spiral annulus: " << m.n_vertices << " vertices, " << m.n_faces << " faces, quad fraction "
            << m.quad_fraction << ", χ = " << m.euler_characteristic << "\n";
  EXPECT_EQ(m.euler_characteristic, 0);
  EXPECT_EQ(m.boundary_loops, 2);
  EXPECT_TRUE(m.interior_non_quads.empty());
  int interior = 0;
  for (const auto v : out.mesh.vertices()) {
    if (out.mesh.is_boundary(v)) continue;
    ++interior;
    EXPECT_EQ(out.mesh.valence(v), 4u) << "vertex " << v.idx();
    // On a radial line and on a spiral (the spiral's value at the vertex's angle on either branch).
    const Eigen::Vector3d p = ToEigen(out.mesh.point(v));
    const double angle = std::atan2(p.y(), p.x());
    const double k = n * angle / (2.0 * M_PI);
    const double j = p.head<2>().norm() - 0.3 + spiral * angle / (2.0 * M_PI);
    EXPECT_NEAR(k, std::round(k), 0.02) << "vertex " << v.idx();
    EXPECT_NEAR(j, std::round(j), 0.02) << "vertex " << v.idx();
  }
  EXPECT_EQ(interior, n * 6);
  EXPECT_EQ(m.n_vertices, n * 8 + 2 * spiral);
}

// Transitions that the values do not satisfy are refused with InvalidInput.
TEST(SeamExtraction, RefusesWrongTransitions) {
  const CutAnnulus annulus = MakeCutAnnulus(1.0);
  const SurfaceModel& s = *annulus.surface;
  const auto& seam_cut = annulus.seam_cut;
  const SurfaceModel& cut = seam_cut->cut();
  const std::vector<double> theta = UnwrappedAngle(cut, Eigen::Vector2d::Zero(), seam_cut->copy_pairs()[0].minus);
  std::vector<double> phi(cut.num_vertices()), psi(cut.num_vertices());
  for (int v = 0; v < cut.num_vertices(); ++v) {
    phi[v] = 12.0 * theta[v] / (2.0 * M_PI);
    psi[v] = cut.position(v).norm();
  }
  const int offset = MeasuredOffset(*seam_cut, 0, 1, phi);
  ExtractedMesh out;
  EXPECT_TRUE(ExtractQuadMesh(s, {seam_cut.get(), {1}, {offset}, {0}}, phi, psi, 30.0, 0.2, &out).ok());
  EXPECT_EQ(ExtractQuadMesh(s, {seam_cut.get(), {1}, {0}, {0}}, phi, psi, 30.0, 0.2, &out).code(),
            StatusCode::kInvalidInput);  // wrong offset
  EXPECT_EQ(ExtractQuadMesh(s, {seam_cut.get(), {-1}, {offset}, {0}}, phi, psi, 30.0, 0.2, &out).code(),
            StatusCode::kInvalidInput);  // wrong sign
  EXPECT_EQ(ExtractQuadMesh(s, {seam_cut.get(), {2}, {offset}, {0}}, phi, psi, 30.0, 0.2, &out).code(),
            StatusCode::kInvalidInput);  // not ±1
  EXPECT_EQ(ExtractQuadMesh(s, {seam_cut.get(), {}, {}, {}}, phi, psi, 30.0, 0.2, &out).code(),
            StatusCode::kInvalidInput);  // one per path
  EXPECT_EQ(ExtractQuadMesh(s, {nullptr, {1}, {offset}, {0}}, phi, psi, 30.0, 0.2, &out).code(),
            StatusCode::kInvalidInput);
  ASSERT_NE(s.num_vertices(), cut.num_vertices());
  const std::vector<double> per_original(s.num_vertices(), 0.5);
  EXPECT_EQ(ExtractQuadMesh(s, {seam_cut.get(), {1}, {offset}, {0}}, per_original, per_original, 30.0, 0.2, &out).code(),
            StatusCode::kInvalidInput);  // values per original vertex, not per cut vertex
}

struct BranchPoint {
  ExtractedMesh out;
  ExtractedMeshMetrics m;
  Eigen::Vector3d tip;
};

// Disk of radius 10 cut from the interior vertex nearest the origin (the tip) to the
// boundary; φ + iψ = c r^m e^{i(kθ + α)} + (shift, shift) about the tip, θ continuous on the
// cut surface. With k = 3/2 (a −½ singularity of both families) or k = ½ (+½), θ jumps by 2π
// and the angle kθ by an odd multiple of π across the seam, so φ₊ = −φ₋ + 2·shift and ψ₊ =
// −ψ₋ + 2·shift (sign −1). k = 3/2: c (z − tip)^{3/2} with c for a level spacing of 1 m at
// radius 5; k = ½: r e^{iθ/2} (spacing 1 to 2 m everywhere).
BranchPoint ExtractBranchPoint(double alpha, double shift, bool pair_boundary_triangles = true, double k = 1.5) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.5));
  const int tip = ClosestInterior(s, 0.0, 0.0);
  const auto paths = RouteSeams(s, std::vector<double>(s.num_faces(), 1.0), {tip});
  EXPECT_EQ(paths.size(), 1u);
  std::unique_ptr<SeamCut> seam_cut;
  EXPECT_TRUE(SeamCut::Build(s, paths, &seam_cut).ok());
  const SurfaceModel& cut = seam_cut->cut();
  const Eigen::Vector2d centre = s.position(tip).head<2>();
  const std::vector<double> theta = UnwrappedAngle(cut, centre, seam_cut->copy_pairs().back().minus);
  const double c = k == 1.5 ? 1.0 / (1.5 * std::sqrt(5.0)) : 1.0;
  const double m = k == 1.5 ? 1.5 : 1.0;
  std::vector<double> phi(cut.num_vertices()), psi(cut.num_vertices());
  for (int v = 0; v < cut.num_vertices(); ++v) {
    const double r = (cut.position(v).head<2>() - centre).norm();
    const double arg = k * theta[v] + alpha;
    phi[v] = c * std::pow(r, m) * std::cos(arg) + shift;
    psi[v] = c * std::pow(r, m) * std::sin(arg) + shift;
  }
  const int a = static_cast<int>(std::lround(2 * shift));
  EXPECT_EQ(MeasuredOffset(*seam_cut, 0, -1, phi), a);
  EXPECT_EQ(MeasuredOffset(*seam_cut, 0, -1, psi), a);
  BranchPoint result;
  result.tip = s.position(tip);
  EXPECT_TRUE(ExtractQuadMesh(s, {seam_cut.get(), {-1}, {a}, {a}}, phi, psi, 30.0, 0.2, &result.out,
                              pair_boundary_triangles)
                  .ok());
  ExpectManifoldWithOrigins(s, result.out);
  result.m = MeasureExtractedMesh(s, result.out, 30.0);
  std::cout << "branch point k = " << k << ", α = " << alpha << ", shift " << shift << ": " << result.m.n_vertices << " vertices, "
            << result.m.n_faces << " faces, quad fraction " << result.m.quad_fraction << ", χ = "
            << result.m.euler_characteristic << ", interior non-quads " << result.m.interior_non_quads.size()
            << ", split interior polygons " << result.out.stats.split_interior_polygons << ", valences";
  for (const auto& [valence, count] : result.m.vertex_valence) std::cout << " " << valence << ":" << count;
  std::cout << "\n";
  EXPECT_EQ(result.m.euler_characteristic, 1);
  EXPECT_EQ(result.m.boundary_loops, 1);
  return result;
}

// Interior vertices of the mesh by valence, and where the irregular ones are.
std::map<int, std::vector<Eigen::Vector3d>> InteriorValences(const PolyMesh& mesh) {
  std::map<int, std::vector<Eigen::Vector3d>> by_valence;
  for (const auto v : mesh.vertices())
    if (!mesh.is_boundary(v)) by_valence[static_cast<int>(mesh.valence(v))].push_back(ToEigen(mesh.point(v)));
  return by_valence;
}

// Branch point at a lattice vertex (offsets 0): three φ lines and three ψ lines end at the
// tip, which becomes the one interior vertex of valence 6; every interior cell is a quad.
TEST(SeamExtraction, BranchPointIsAValenceSixVertex) {
  for (const double alpha : {0.0, 0.4}) {  // ψ = 0 along the seam, or no level line along it
    SCOPED_TRACE(alpha);
    const BranchPoint b = ExtractBranchPoint(alpha, 0.0);
    EXPECT_TRUE(b.m.interior_non_quads.empty());
    const auto valences = InteriorValences(b.out.mesh);
    ASSERT_EQ(valences.count(6), 1u);
    ASSERT_EQ(valences.at(6).size(), 1u);
    EXPECT_LE((valences.at(6)[0] - b.tip).norm(), 1e-12);
    for (const auto& [valence, points] : valences) EXPECT_TRUE(valence == 4 || valence == 6) << "valence " << valence;
  }
}

// Branch point inside a cell (offsets 1: the tip at φ = ψ = ½): the cell round the tip is
// bounded by 6 curve segments (the level lines turn by 3π round it), one interior hexagon;
// the splitting of large cells (on with pair_boundary_triangles) cuts it into two quads,
// leaving two interior vertices of valence 5 next to the tip.
TEST(SeamExtraction, BranchPointInsideACellIsAHexagonOrTwoQuads) {
  const BranchPoint hexagon = ExtractBranchPoint(0.4, 0.5, false);
  ASSERT_EQ(hexagon.m.interior_non_quads.size(), 1u);
  EXPECT_EQ(hexagon.m.interior_non_quads[0].first, 6);
  const double from_tip = (hexagon.m.interior_non_quads[0].second - hexagon.tip).norm();
  std::cout << "hexagon centroid " << from_tip << " m from the tip\n";
  EXPECT_LE(from_tip, 0.1);  // measured 0.0014: the hexagon is symmetric about the tip (3-fold)
  for (const auto& [valence, points] : InteriorValences(hexagon.out.mesh)) EXPECT_EQ(valence, 4);

  const BranchPoint split = ExtractBranchPoint(0.4, 0.5);
  EXPECT_EQ(split.out.stats.split_interior_polygons, 1);
  EXPECT_TRUE(split.m.interior_non_quads.empty());
  const auto valences = InteriorValences(split.out.mesh);
  ASSERT_EQ(valences.count(5), 1u);
  EXPECT_EQ(valences.at(5).size(), 2u);
  for (const auto& p : valences.at(5)) EXPECT_LE((p - split.tip).norm(), 4.0);
  for (const auto& [valence, points] : valences) EXPECT_TRUE(valence == 4 || valence == 5) << "valence " << valence;
}

// A +½ singularity of both families at a lattice vertex (k = ½, offsets 0): only two cells
// meet at the tip (the curves turn by π round it), so it is no mesh vertex; the φ line and
// the ψ line that end there form one curve through it, and the two cells beside the tip are
// triangles (a valence-2 vertex cannot be). Everything else stays quads of valence-4
// vertices; the identification itself is exact (no unmatched seam edges).
TEST(SeamExtraction, PlusHalfTipGivesTwoTriangles) {
  for (const double alpha : {0.0, 0.4, 1.1}) {
    SCOPED_TRACE(alpha);
    const BranchPoint b = ExtractBranchPoint(alpha, 0.0, true, 0.5);
    ASSERT_EQ(b.m.interior_non_quads.size(), 2u);
    for (const auto& [sides, centroid] : b.m.interior_non_quads) {
      EXPECT_EQ(sides, 3);
      EXPECT_LE((centroid - b.tip).norm(), 1.0);  // measured 0.47
    }
    for (const auto& [valence, points] : InteriorValences(b.out.mesh)) EXPECT_EQ(valence, 4);
    for (const auto v : b.out.mesh.vertices()) EXPECT_GT((ToEigen(b.out.mesh.point(v)) - b.tip).norm(), 0.1);
  }
}

// A seam across which nothing jumps (sign +1, offsets 0, the same value on both copies)
// must give exactly the seam-free mesh.
void ExpectSameAsWithoutSeams(const SurfaceModel& s, const std::vector<int>& tips, double angle, double h) {
  const auto paths = RouteSeams(s, std::vector<double>(s.num_faces(), 1.0), tips);
  ASSERT_GE(paths.size(), 1u);
  std::unique_ptr<SeamCut> seam_cut;
  ASSERT_TRUE(SeamCut::Build(s, paths, &seam_cut).ok());
  std::vector<double> phi, psi;
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d p = s.position(v);
    phi.push_back((std::cos(angle) * p.x() + std::sin(angle) * p.y()) / h + 0.37);
    psi.push_back((-std::sin(angle) * p.x() + std::cos(angle) * p.y()) / h + 0.37);
  }
  const int np = seam_cut->num_paths();
  const SeamTransitions transitions{seam_cut.get(), std::vector<int>(np, 1), std::vector<int>(np, 0),
                                    std::vector<int>(np, 0)};
  ExtractedMesh plain, seamed;
  ASSERT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, 0.2 * h, &plain).ok());
  ASSERT_TRUE(ExtractQuadMesh(s, transitions, seam_cut->ToCut(phi), seam_cut->ToCut(psi), 30.0, 0.2 * h, &seamed).ok());
  EXPECT_EQ(seamed.stats.unmatched_seam_edges, 0);
  EXPECT_EQ(seamed.stats.seam_transition_mismatch, 0.0);
  ASSERT_EQ(seamed.mesh.n_vertices(), plain.mesh.n_vertices());
  ASSERT_EQ(seamed.mesh.n_faces(), plain.mesh.n_faces());
  for (const auto v : plain.mesh.vertices()) {
    EXPECT_EQ(seamed.mesh.point(v), plain.mesh.point(v)) << "vertex " << v.idx();
    EXPECT_EQ(seamed.origin[v.idx()].face, plain.origin[v.idx()].face);
    EXPECT_EQ(seamed.origin[v.idx()].barycentric, plain.origin[v.idx()].barycentric);
    EXPECT_EQ(seamed.origin[v.idx()].on_boundary, plain.origin[v.idx()].on_boundary);
    EXPECT_EQ(seamed.origin[v.idx()].corner, plain.origin[v.idx()].corner);
  }
  for (const auto f : plain.mesh.faces()) {
    std::vector<int> a, b;
    for (const auto v : plain.mesh.fv_range(f)) a.push_back(v.idx());
    for (const auto v : seamed.mesh.fv_range(f)) b.push_back(v.idx());
    EXPECT_EQ(a, b) << "face " << f.idx();
  }
  std::cout << "seam with no jump: " << plain.mesh.n_vertices() << " vertices, " << plain.mesh.n_faces()
            << " faces, identical\n";
}

TEST(SeamExtraction, SeamWithoutJumpChangesNothing) {
  {
    SCOPED_TRACE("disk with a tip");
    const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.7));
    ExpectSameAsWithoutSeams(s, {ClosestInterior(s, 2.0, 1.0), ClosestInterior(s, -3.0, -2.0)}, 0.3, 2.0);
  }
  {
    SCOPED_TRACE("annulus");
    const SurfaceModel s(GeneratedMesh("annulus", 20.0, 8.0, 0.0, 0.7));
    ExpectSameAsWithoutSeams(s, {}, 0.5, 1.5);
  }
  {
    SCOPED_TRACE("dome, corners");
    const SurfaceModel s(GeneratedMesh("dome", 20.0, 16.0, 3.0, 0.8));
    ExpectSameAsWithoutSeams(s, {ClosestInterior(s, 1.0, 0.5)}, 0.2, 1.7);
  }
}

}  // namespace
}  // namespace pqlayout
