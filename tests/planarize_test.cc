// Planarisation: the δ metric on hand-computed cases, GradientChecker on every residual
// functor, and known answers — a noisy planar grid returns to exact planarity on its plane,
// a quad strip on a cylinder (developable: planar strips exist on it) becomes planar while
// staying on the cylinder.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <memory>

#include <cmath>
#include <random>
#include <limits>
#include <algorithm>

#include "geometry/panel_repair.h"
#include "geometry/planarity.h"
#include "problems/planarize.h"
#include "problems/residuals/anchor_residual.h"
#include "problems/residuals/edge_length_residual.h"
#include "problems/residuals/triangle_orientation_residual.h"
#include "problems/residuals/boundary_residual.h"
#include "problems/residuals/closeness_residual.h"
#include "problems/residuals/fairness_residual.h"
#include "problems/residuals/planarity_residual.h"
#include "problems/residuals/surface_chart_manifold.h"
#include "tests/gradient_check.h"
#include "tests/quad_grid.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::QuadGrid;

std::mt19937 rng(7);
double Uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

TEST(PlanarityDelta, HandComputedValues) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
  EXPECT_EQ(PlanarityDelta({a, b, c, d}), 0.0);
  // Lift one corner by 0.2: the diagonals a–c (direction (1, 1, 0)) and b–d' (direction
  // (−1, 1, 0.2)) are skew; their common normal is (0.2, −0.2, 2), so their distance is
  // |(b − a) · n| / |n| = 0.2 / √4.08; the mean diagonal length is (√2 + √2.04) / 2.
  const Eigen::Vector3d d2(0, 1, 0.2);
  const double mean_diagonal = 0.5 * (std::sqrt(2.0) + std::sqrt(2.04));
  EXPECT_NEAR(PlanarityDelta({a, b, c, d2}), 0.2 / std::sqrt(4.08) / mean_diagonal, 1e-12);
  std::vector<Eigen::Vector3d> hexagon;
  for (int k = 0; k < 6; ++k) hexagon.emplace_back(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0.0);
  EXPECT_NEAR(PlanarityDelta(hexagon), 0.0, 1e-15);
  hexagon[2].z() = 0.3;
  EXPECT_GT(PlanarityDelta(hexagon), 0.01);
  EXPECT_EQ(PlanarityDelta({a, b, d2}), 0.0);
}

void Check(const std::string& name, ceres::CostFunction* cost, const std::vector<std::vector<double>>& blocks,
           const std::vector<const ceres::Manifold*>* manifolds = nullptr) {
  testing::ExpectJacobiansMatchFiniteDifferences(name, cost, blocks, manifolds);
}

std::vector<double> RandomBlock(int n) {
  std::vector<double> b(n);
  for (double& x : b) x = Uniform(-2, 2);
  return b;
}

// A gently curved reference over [0, 6]²: z = 0.3 sin(x) cos(0.7 y).
SurfaceModel WavyReference() {
  return SurfaceModel(testing::ToMesh(
      testing::GridSoup(12, [](double x, double y) { return 0.3 * std::sin(x) * std::cos(0.7 * y); })));
}

TEST(PlanarizeResiduals, GradientCheckAtRandomPoints) {
  const SurfaceModel reference = WavyReference();
  const ClosestPointQuery query(reference);
  ceres::ProductManifold<ceres::SphereManifold<3>, ceres::EuclideanManifold<1>> plane_manifold;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Vector3d n = Eigen::Vector3d::Random().normalized();
    const std::vector<const ceres::Manifold*> planarity_manifolds{&plane_manifold, nullptr};
    Check("planarity", PlanarityResidual::Create(Uniform(0.5, 5), Uniform(1, 4), Eigen::Vector3d::Random()),
          {{n.x(), n.y(), n.z(), Uniform(-2, 2)}, RandomBlock(3)}, &planarity_manifolds);
    // Off the middle of a random reference triangle along its normal (the closest point is
    // then inside that triangle, where the distance is smooth).
    const int t = static_cast<int>(Uniform(0, reference.num_faces() - 1));
    const auto ids = reference.face_vertices(t);
    const Eigen::Vector3d centre = (reference.position(ids[0]) + reference.position(ids[1]) + reference.position(ids[2])) / 3.0;
    const Eigen::Vector3d p = centre + Uniform(-0.05, 0.05) * reference.face_normal(t);
    Check("closeness", new ClosenessResidual(&query, 2.0, 3.0), {{p.x(), p.y(), p.z()}});
    // Near the middle of an edge of the boundary y = 0 (its vertices are 0.5 m apart).
    const double middle = 0.5 * static_cast<int>(Uniform(1, 10)) + 0.25;
    Check("boundary", new BoundaryResidual(&query, 2.0, 3.0),
          {{middle + Uniform(-0.05, 0.05), Uniform(-0.05, 0.05), 0.3 * std::sin(middle) + Uniform(-0.05, 0.05)}});
    Check("anchor", AnchorResidual::Create(Eigen::Vector3d::Random(), 2.0, 3.0), {RandomBlock(3)});
    Check("fairness", FairnessResidual::Create(0.3, 3.0), {RandomBlock(3), RandomBlock(3), RandomBlock(3)});
    // The edge-length hinge where it is active (the points closer than ℓ_min = 2).
    const std::vector<double> a = RandomBlock(3);
    std::vector<double> b = a;
    for (int k = 0; k < 3; ++k) b[k] += Uniform(-0.5, 0.5);
    Check("edge_length", EdgeLengthResidual::Create(2.0, 2.0, 3.0), {a, b});
    // The orientation hinge where it is active: κ = 2 of A₀ = 1 is more than any of these
    // triangles' signed areas (their corners within a unit cube).
    Check("triangle_orientation",
          TriangleOrientationResidual::Create(Eigen::Vector3d::Random().normalized(), 1.0, 2.0, 3.0),
          {RandomBlock(3), RandomBlock(3), RandomBlock(3)});
  }
}

// The orientation hinge is zero while the triangle keeps κ of its area A₀ round n₀ and grows
// linearly below, through zero area to turned over: r = √w (κ − n₀·(e₁ × e₂) / (2 A₀)).
TEST(PlanarizeResiduals, TriangleOrientationHingeValues) {
  std::unique_ptr<ceres::CostFunction> cost(
      TriangleOrientationResidual::Create(Eigen::Vector3d::UnitZ(), 0.5, 0.25, 4.0));
  const auto residual = [&](double apex_y) {  // the unit right triangle with its apex at (0, y)
    const double p0[3] = {1.0, 2.0, 3.0}, p1[3] = {2.0, 2.0, 3.0}, p2[3] = {1.0, 2.0 + apex_y, 3.0};
    const double* blocks[3] = {p0, p1, p2};
    double r = -1.0;
    EXPECT_TRUE(cost->Evaluate(blocks, &r, nullptr));
    return r;
  };
  EXPECT_EQ(residual(1.0), 0.0);                    // as it was
  EXPECT_EQ(residual(0.3), 0.0);                    // 0.3 of its area: above κ
  EXPECT_NEAR(residual(0.1), 2.0 * 0.15, 1e-15);    // 0.1 of it: √w (κ − 0.1)
  EXPECT_NEAR(residual(0.0), 2.0 * 0.25, 1e-15);    // flat
  EXPECT_NEAR(residual(-1.0), 2.0 * 1.25, 1e-15);   // turned over
}

// The hinge is zero while the edge is at least ℓ_min long and grows linearly below it:
// r = √w (ℓ_min − ℓ) / h.
TEST(PlanarizeResiduals, EdgeLengthHingeValues) {
  std::unique_ptr<ceres::CostFunction> cost(EdgeLengthResidual::Create(0.5, 4.0, 2.0));
  const auto residual = [&](double length) {
    const double p[3] = {1.0, 2.0, 3.0}, q[3] = {1.0 + length * 0.6, 2.0 + length * 0.8, 3.0};
    const double* blocks[2] = {p, q};
    double r = -1.0;
    EXPECT_TRUE(cost->Evaluate(blocks, &r, nullptr));
    return r;
  };
  EXPECT_NEAR(residual(0.5), 0.0, 1e-15);  // at ℓ_min (up to rounding of the offset)
  EXPECT_EQ(residual(3.0), 0.0);
  EXPECT_NEAR(residual(0.3), 2.0 * 0.2 / 2.0, 1e-15);
  EXPECT_NEAR(residual(0.0), 2.0 * 0.5 / 2.0, 1e-15);
}

TEST(SurfaceManifold, StepsStayOnTheReferenceAndPlusJacobianIsTheTangentBasis) {
  const SurfaceModel reference = WavyReference();
  const ClosestPointQuery query(reference);
  const SurfaceManifold inside(&query, false), boundary(&query, true);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d x = query.OnSurface({Uniform(1, 5), Uniform(1, 5), 0.0}).point;
    const double delta[2] = {Uniform(-1, 1), Uniform(-1, 1)};
    Eigen::Vector3d y;
    ASSERT_TRUE(inside.Plus(x.data(), delta, y.data()));
    EXPECT_LT(query.OnSurface(y).distance, 1e-12);
    // At δ = 0 the Jacobian of Plus is the basis of the triangle's plane: orthonormal and
    // perpendicular to the triangle's normal.
    double jacobian[6];
    ASSERT_TRUE(inside.PlusJacobian(x.data(), jacobian));
    const Eigen::Map<const Eigen::Matrix<double, 3, 2, Eigen::RowMajor>> B(jacobian);
    EXPECT_NEAR((B.transpose() * B - Eigen::Matrix2d::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((B.transpose() * query.OnSurface(x).normal).norm(), 0.0, 1e-12);
    // A small step is the tangent step (no retraction needed inside the triangle).
    const double tiny[2] = {1e-7, -2e-7};
    ASSERT_TRUE(inside.Plus(x.data(), tiny, y.data()));
    EXPECT_NEAR((y - x - B * Eigen::Vector2d(tiny[0], tiny[1])).norm(), 0.0, 1e-12);
    // A boundary vertex slides along the boundary polyline.
    const Eigen::Vector3d b = query.OnBoundary({Uniform(1, 5), 0.0, 0.0}).point;
    const double along = Uniform(-3, 3);
    ASSERT_TRUE(boundary.Plus(b.data(), &along, y.data()));
    EXPECT_LT(query.OnBoundary(y).distance, 1e-12);
  }
}

// A hint (any triangle / boundary edge, near or far) only speeds the search up: the answer is
// the same closest point as without one.
TEST(ClosestPointQuery, HintedSearchGivesTheSameClosestPoint) {
  const SurfaceModel reference = WavyReference();
  const ClosestPointQuery query(reference);
  int boundary_edges = 0;
  for (const auto& loop : reference.boundary_loops()) boundary_edges += static_cast<int>(loop.vertices.size());
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d p(Uniform(-1, 7), Uniform(-1, 7), Uniform(-1, 1));
    const SurfacePoint free = query.OnSurface(p);
    const SurfacePoint hinted = query.OnSurface(p, static_cast<int>(Uniform(0, reference.num_faces() - 1)));
    EXPECT_NEAR(hinted.distance, free.distance, 1e-12);
    EXPECT_NEAR((hinted.point - free.point).norm(), 0.0, 1e-9);
    const SurfacePoint edge = query.OnBoundary(p), hinted_edge = query.OnBoundary(p, static_cast<int>(Uniform(0, boundary_edges - 1)));
    EXPECT_NEAR(hinted_edge.distance, edge.distance, 1e-12);
    EXPECT_NEAR((hinted_edge.point - edge.point).norm(), 0.0, 1e-9);
    // The boundary answer is the closest point of the boundary polylines (brute force).
    double best = std::numeric_limits<double>::infinity();
    for (const auto& loop : reference.boundary_loops())
      for (size_t i = 0; i < loop.vertices.size(); ++i) {
        const Eigen::Vector3d a = reference.position(loop.vertices[i]);
        const Eigen::Vector3d ab = reference.position(loop.vertices[(i + 1) % loop.vertices.size()]) - a;
        best = std::min(best, (a + std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) * ab - p).norm());
      }
    EXPECT_NEAR(edge.distance, best, 1e-12);
  }
}

// Every field of two closest-point answers equal, to the bit.
void ExpectSameAnswer(const SurfacePoint& a, const SurfacePoint& b) {
  EXPECT_EQ(a.element, b.element);
  EXPECT_EQ(a.point, b.point);
  EXPECT_EQ(a.normal, b.normal);
  EXPECT_EQ(a.tangent, b.tangent);
  EXPECT_EQ(a.inside_edge, b.inside_edge);
  EXPECT_EQ(a.distance, b.distance);
}

// The index built on another thread (SurfaceModel::IndexClosestPointsInBackground) answers
// exactly as one built in line: every field of every answer the same, surface and boundary;
// asked twice, the surface hands out the same index.
TEST(ClosestPointQuery, IndexedInTheBackgroundGivesTheSameAnswers) {
  const SurfaceModel reference = WavyReference();
  const ClosestPointQuery in_line(reference);
  const SurfaceModel indexed = WavyReference();
  indexed.IndexClosestPointsInBackground();
  indexed.IndexClosestPointsInBackground();  // a second call while the first runs: ignored
  const ClosestPointQuery& background = indexed.closest_points();
  EXPECT_EQ(&background, &indexed.closest_points());
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d p(Uniform(-1, 7), Uniform(-1, 7), Uniform(-1, 1));
    for (const bool boundary : {false, true}) {
      ExpectSameAnswer(boundary ? in_line.OnBoundary(p) : in_line.OnSurface(p),
                       boundary ? background.OnBoundary(p) : background.OnSurface(p));
    }
  }
}

// RememberedClosestPoint (planarisation's closeness and boundary residuals): every answer,
// from memory or searched with the last one as hint, is the query's own to the bit — also
// back at a point asked two questions ago (a memory keyed on anything but the exact position
// would answer that with the point in between), and for points that moved by one ulp.
TEST(ClosestPoints, RememberedAnswersAreTheQuerysOwn) {
  const SurfaceModel s(testing::ToMesh(testing::GridSoup(6, [](double x, double y) { return std::sin(x) * std::cos(0.7 * y); })));
  const ClosestPointQuery& query = s.closest_points();
  const auto expect_same = ExpectSameAnswer;
  const Eigen::Vector3d p1(2.3, 1.7, 0.4), p2(2.35, 1.7, 0.4), p3(5.1, 0.2, -0.8);
  const Eigen::Vector3d p1_next(std::nextafter(p1.x(), 3.0), p1.y(), p1.z());
  RememberedClosestPoint on_surface, on_boundary;
  int surface_elements = 0;
  for (const Eigen::Vector3d& p : {p1, p1, p2, p1, p1_next, p3, p3, p1}) {
    const SurfacePoint fresh = query.OnSurface(p);
    expect_same(on_surface.OnSurface(query, p), fresh);
    expect_same(on_boundary.OnBoundary(query, p), query.OnBoundary(p));
    surface_elements += fresh.element >= 0;
  }
  EXPECT_EQ(surface_elements, 8);
  // The points are not all answered alike: the test would not see a memory that ignored p.
  EXPECT_NE(query.OnSurface(p1).element, query.OnSurface(p3).element);
  EXPECT_NE(query.OnSurface(p1).point, query.OnSurface(p2).point);
}

// The manifold remembers the triangles of its last two points. A step from the same state
// after a rejected candidate is what a fresh manifold computes, and the chart at an accepted
// candidate is the plane of a triangle the candidate lies on: a tangent step of 1e-7 into that
// triangle needs no retraction (a stale chart — the previous point's triangle, tilted by up to
// 0.1 rad here — would be off the surface by ~1e-8).
TEST(SurfaceManifold, RememberedTrianglesGiveTheFreshAnswers) {
  const SurfaceModel reference = WavyReference();
  const ClosestPointQuery query(reference);
  const SurfaceManifold kept(&query, false);
  Eigen::Vector3d x = query.OnSurface({3.1, 2.9, 0.0}).point;
  for (int trial = 0; trial < 50; ++trial) {
    const double delta[2] = {Uniform(-0.3, 0.3), Uniform(-0.3, 0.3)};
    Eigen::Vector3d y, y_fresh;
    ASSERT_TRUE(kept.Plus(x.data(), delta, y.data()));
    ASSERT_TRUE(SurfaceManifold(&query, false).Plus(x.data(), delta, y_fresh.data()));
    EXPECT_NEAR((y - y_fresh).norm(), 0.0, 1e-12);
    if (trial % 2 == 0) continue;  // "rejected": the next step starts from x again
    double jacobian[6];
    ASSERT_TRUE(kept.PlusJacobian(y.data(), jacobian));
    const Eigen::Map<const Eigen::Matrix<double, 3, 2, Eigen::RowMajor>> B(jacobian);
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 16; ++k) {  // 16 directions: one points into the triangle even at a vertex
      const double tiny[2] = {1e-7 * std::cos(k * M_PI / 8), 1e-7 * std::sin(k * M_PI / 8)};
      Eigen::Vector3d z;
      ASSERT_TRUE(kept.Plus(y.data(), tiny, z.data()));
      best = std::min(best, (z - y - B * Eigen::Vector2d(tiny[0], tiny[1])).norm());
    }
    EXPECT_LT(best, 1e-13);
    x = y;  // "accepted"
  }
}


// A panel that planarisation folded is cut into a fan of triangles (SplitFoldedPanels), and
// the next pass must open them even when every quad is planar already: planarity cannot see a
// triangle inside out. A flat 3 × 3 grid with its interior vertex (1, 1) pushed to (2.3, 2.3),
// past the vertex (2, 2): the panels it folded, cut, leave triangles inside out, and δ is 0
// everywhere. Before the rounds also waited for the triangles, the pass did nothing and they
// stayed folded (2 on the Great Court × strain with the seams' offsets rounded together).
TEST(Planarize, TrianglesCutFromAFoldedPanelAreOpenedWhenEveryQuadIsPlanar) {
  auto flat = [](double, double) { return 0.0; };
  const SurfaceModel reference(testing::ToMesh(testing::GridSoup(3, flat)));
  ExtractedMesh grid = QuadGrid(3, 3, 1.0, flat);
  std::vector<Eigen::Vector3d> start;
  for (const auto v : grid.mesh.vertices()) start.push_back(ToEigen(grid.mesh.point(v)));
  grid.mesh.set_point(VertexHandle(5), {2.3, 2.3, 0.0});
  ASSERT_GE(SplitFoldedPanels(start, &grid), 1);
  PlanarizeReport before;
  MeasurePanelShapes(grid.mesh, start, 1.0, 0.2, &before);
  ASSERT_GE(before.folded_faces, 1);  // a triangle of the fan is inside out
  PlanarizeReport report;
  ASSERT_TRUE(PlanarizeMesh(reference, PlanarizeOptions(), 1.0, &grid, &report, &start).ok());
  EXPECT_GE(report.rounds, 1);
  EXPECT_LE(report.planarity_max, 1e-12);
  PlanarizeReport after;
  MeasurePanelShapes(grid.mesh, start, 1.0, 0.2, &after);
  EXPECT_EQ(after.folded_faces, 0);
}

// A mesh of triangles only has no plane for the steps' Schur complement to eliminate
// (SetStepSolver keeps the sparse factor then): a triangle turned inside out is still opened,
// on the reference.
TEST(Planarize, AMeshWithoutQuadsStillOpensItsInsideOutTriangle) {
  auto flat = [](double, double) { return 0.0; };
  const SurfaceModel reference(testing::ToMesh(testing::GridSoup(3, flat)));
  const ExtractedMesh grid = QuadGrid(3, 3, 1.0, flat);
  ExtractedMesh triangles;
  triangles.origin = grid.origin;
  std::vector<Eigen::Vector3d> start;
  for (const auto v : grid.mesh.vertices()) {
    triangles.mesh.add_vertex(grid.mesh.point(v));
    start.push_back(ToEigen(grid.mesh.point(v)));
  }
  for (const auto f : grid.mesh.faces()) {
    std::vector<VertexHandle> q;
    for (const auto v : grid.mesh.fv_range(f)) q.push_back(v);
    triangles.mesh.add_face({q[0], q[1], q[2]});
    triangles.mesh.add_face({q[0], q[2], q[3]});
  }
  triangles.mesh.set_point(VertexHandle(5), {2.4, 2.4, 0.0});  // past its ring: triangles fold over
  PlanarizeReport before;
  MeasurePanelShapes(triangles.mesh, start, 1.0, 0.2, &before);
  ASSERT_GE(before.folded_faces, 1);
  PlanarizeReport report;
  ASSERT_TRUE(PlanarizeMesh(reference, PlanarizeOptions(), 1.0, &triangles, &report, &start).ok());
  EXPECT_GE(report.rounds, 1);  // there was work, with no plane in the problem
  EXPECT_EQ(report.planarity_max, 0.0);
  EXPECT_LE(report.closeness_max, 1e-9);
  PlanarizeReport after;
  MeasurePanelShapes(triangles.mesh, start, 1.0, 0.2, &after);
  EXPECT_EQ(after.folded_faces, 0);
}

TEST(Planarize, NoisyPlanarGridReturnsToItsPlane) {
  auto flat = [](double, double) { return 0.0; };
  const SurfaceModel reference(testing::ToMesh(testing::GridSoup(6, flat)));
  ExtractedMesh grid = QuadGrid(6, 6, 1.0, flat);
  for (const auto v : grid.mesh.vertices()) {
    if (grid.origin[v.idx()].on_boundary) continue;
    auto p = grid.mesh.point(v);
    p[0] += Uniform(-0.1, 0.1);  // along the plane
    p[1] += Uniform(-0.1, 0.1);
    p[2] += Uniform(-0.05, 0.05);  // off it
    grid.mesh.set_point(v, p);
  }
  PlanarizeOptions options;
  options.target_delta = 1e-7;
  PlanarizeReport report;
  ASSERT_TRUE(PlanarizeMesh(reference, options, 1.0, &grid, &report).ok());
  EXPECT_LE(report.planarity_max, 1e-6);
  EXPECT_LE(report.closeness_max, 1e-6 * 6.0);
  for (const auto v : grid.mesh.vertices()) EXPECT_NEAR(grid.mesh.point(v)[2], 0.0, 1e-6 * 6.0);
  EXPECT_LE(report.max_displacement, 0.1);  // the noise, no more: the grid was planar already
}

// A jittered grid of 6 × 6 unit quads on the cylinder z = √(R² − (x − 3)²), R = 8 (rulings
// along y: a quad whose two x-columns are rulings is planar; the jitter across the rulings
// makes them not), all of it moved by `offset`; and the cylinder as a fine reference.
struct CylinderStrip {
  SurfaceModel cylinder;
  ExtractedMesh strip;
};
CylinderStrip JitteredCylinderStrip(const Eigen::Vector3d& offset, unsigned seed) {
  const double R = 8.0;
  auto height = [R](double x, double) { return std::sqrt(R * R - (x - 3.0) * (x - 3.0)); };
  PolygonSoup soup = testing::GridSoup(30, [](double, double) { return 0.0; });
  for (auto& p : soup.points) {
    p.x() *= 0.2;
    p.y() *= 0.2;
    p.z() = height(p.x(), p.y());
    p += offset;
  }
  ExtractedMesh strip = QuadGrid(6, 6, 1.0, height);
  std::mt19937 jitter(seed);
  for (const auto v : strip.mesh.vertices()) {
    auto p = strip.mesh.point(v);
    if (!strip.origin[v.idx()].on_boundary) {
      p[0] += std::uniform_real_distribution<double>(-0.15, 0.15)(jitter);  // off the rulings
      p[2] = height(p[0], p[1]);
    }
    strip.mesh.set_point(v, p + OpenMesh::Vec3d(offset.x(), offset.y(), offset.z()));
  }
  return {SurfaceModel(testing::ToMesh(soup)), std::move(strip)};
}

TEST(Planarize, QuadStripOnACylinderBecomesPlanarAndStaysOnIt) {
  const double R = 8.0, h = 1.0;
  auto [cylinder, strip] = JitteredCylinderStrip(Eigen::Vector3d::Zero(), 7);
  PlanarizeReport report;
  ASSERT_TRUE(PlanarizeMesh(cylinder, PlanarizeOptions(), h, &strip, &report).ok());
  EXPECT_LE(report.planarity_max, 1e-3);
  EXPECT_LE(report.closeness_max, 1e-3 * h);  // to the reference triangle mesh
  for (const auto v : strip.mesh.vertices()) {  // to the cylinder itself (the mesh's chord error is 6e-4 m)
    const auto p = strip.mesh.point(v);
    EXPECT_LE(std::abs(std::hypot(p[0] - 3.0, p[2]) - R), 1e-3 * h);
  }
  EXPECT_GE(report.rounds, 1);  // it really had work to do
  std::cout << "cylinder strip: δ max " << report.planarity_max << ", closeness max " << report.closeness_max
            << " m after " << report.rounds << " rounds\n";
}

// From 1,000 faces on, each step is solved over the vertices only (the planes eliminated,
// conjugate gradients: SetStepSolver). 24 × 60 quads of 0.25 m on the cylinder (as above,
// jittered off the rulings) still end planar, on the reference and on the cylinder; a 6 × 6
// strip keeps the sparse factor on the surface.
TEST(Planarize, ALargeStripIsSolvedOverItsVerticesAndEndsPlanarOnTheCylinder) {
  const double R = 8.0, h = 0.25;
  auto height = [R](double x, double) { return std::sqrt(R * R - (x - 3.0) * (x - 3.0)); };
  PolygonSoup soup = testing::GridSoup(60, [](double, double) { return 0.0; });
  for (auto& p : soup.points) {  // 6 m across the rulings (0.1 m chords: 1.6e-4 m off), 15 m along
    p.x() *= 0.1;
    p.y() *= 0.25;
    p.z() = height(p.x(), p.y());
  }
  const SurfaceModel cylinder(testing::ToMesh(soup));
  ExtractedMesh strip = QuadGrid(24, 60, h, height);
  std::mt19937 jitter(5);
  for (const auto v : strip.mesh.vertices()) {
    if (strip.origin[v.idx()].on_boundary) continue;
    auto p = strip.mesh.point(v);
    p[0] += std::uniform_real_distribution<double>(-0.15 * h, 0.15 * h)(jitter);
    p[2] = height(p[0], p[1]);
    strip.mesh.set_point(v, p);
  }
  PlanarizeReport report;
  ASSERT_TRUE(PlanarizeMesh(cylinder, PlanarizeOptions(), h, &strip, &report).ok());
  ASSERT_GE(report.ceres.size(), 1u);
  for (const auto& round : report.ceres) EXPECT_EQ(round["linear_solver"], "ITERATIVE_SCHUR");
  EXPECT_LE(report.planarity_max, 1e-3);
  EXPECT_LE(report.closeness_max, 1e-3 * h);
  double off = 0.0;
  for (const auto v : strip.mesh.vertices()) {
    const auto p = strip.mesh.point(v);
    off = std::max(off, std::abs(std::hypot(p[0] - 3.0, p[2]) - R));
  }
  EXPECT_LE(off, 1.6e-4 + 1e-3 * h);
  auto [small_cylinder, small] = JitteredCylinderStrip(Eigen::Vector3d::Zero(), 7);
  PlanarizeReport small_report;
  ASSERT_TRUE(PlanarizeMesh(small_cylinder, PlanarizeOptions(), 1.0, &small, &small_report).ok());
  ASSERT_GE(small_report.ceres.size(), 1u);
  EXPECT_EQ(small_report.ceres[0]["linear_solver"], "SPARSE_NORMAL_CHOLESKY");
  std::cout << "1,440 quads: δ max " << report.planarity_max << ", closeness max " << report.closeness_max << " m, "
            << off << " m off the cylinder after " << report.rounds << " rounds\n";
}

// Planarisation does not depend on where the roof lies: the same strip 5 km from the origin
// (a georeferenced file the local frame does not catch, or a roof on a large site) takes the
// same rounds to the same panels. With each face's plane offset measured from the origin
// (n · p − d) it took 3 rounds instead of 2 there, moved vertices 0.59 m instead of 0.16 m,
// and its panels ended 0.58 m from the near strip's: the normal equations' (n, d) block is
// conditioned like (|p| / ℓ)².
TEST(Planarize, ARoofFarFromTheOriginIsPlanarisedAsAtTheOrigin) {
  const Eigen::Vector3d far(5000.0, -3000.0, 120.0);
  auto near_case = JitteredCylinderStrip(Eigen::Vector3d::Zero(), 11);
  auto far_case = JitteredCylinderStrip(far, 11);
  PlanarizeReport near_report, far_report;
  ASSERT_TRUE(PlanarizeMesh(near_case.cylinder, PlanarizeOptions(), 1.0, &near_case.strip, &near_report).ok());
  ASSERT_TRUE(PlanarizeMesh(far_case.cylinder, PlanarizeOptions(), 1.0, &far_case.strip, &far_report).ok());
  EXPECT_LE(far_report.planarity_max, 1e-3);
  EXPECT_EQ(far_report.rounds, near_report.rounds);
  EXPECT_NEAR(far_report.max_displacement, near_report.max_displacement, 1e-3);
  double apart = 0.0;
  for (const auto v : near_case.strip.mesh.vertices()) {
    const auto p = near_case.strip.mesh.point(v), q = far_case.strip.mesh.point(v);
    apart = std::max(apart, (Eigen::Vector3d(q[0], q[1], q[2]) - far - Eigen::Vector3d(p[0], p[1], p[2])).norm());
  }
  EXPECT_LE(apart, 1e-3);  // m, on 1 m quads
  std::cout << "rounds " << near_report.rounds << " / " << far_report.rounds << ", moved " << near_report.max_displacement
            << " / " << far_report.max_displacement << " m, panels " << apart << " m apart\n";
}

}  // namespace
}  // namespace pqlayout
