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
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

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

// A quad grid over a reference triangulation of the same rectangle; z = height(x, y).
template <typename Height>
ExtractedMesh QuadGrid(int nx, int ny, double cell, Height height) {
  ExtractedMesh out;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = i * cell, y = j * cell;
      out.mesh.add_vertex({x, y, height(x, y)});
      QuadMeshVertex origin;
      origin.on_boundary = i == 0 || j == 0 || i == nx || j == ny;
      origin.corner = (i == 0 || i == nx) && (j == 0 || j == ny);
      out.origin.push_back(origin);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int v = j * (nx + 1) + i;
      out.mesh.add_face({VertexHandle(v), VertexHandle(v + 1), VertexHandle(v + nx + 2), VertexHandle(v + nx + 1)});
    }
  return out;
}

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
  ASSERT_EQ(SplitWarpedPanels(0.05, &grid), 1);
  EXPECT_EQ(FaceSides(grid.mesh), (std::map<int, int>{{3, 2}, {4, 1}}));
  EXPECT_EQ(grid.mesh.n_vertices(), 6u);
  EXPECT_EQ(diagonal(grid), (std::set<int>{2, 4}));
  grid = warped({2.8, 1.0, 0.3}, {2.0, 0.0, 0.0});
  ASSERT_EQ(SplitWarpedPanels(0.05, &grid), 1);
  EXPECT_EQ(diagonal(grid), (std::set<int>{2, 4}));
  grid = warped({2.0, 1.0, 0.3}, {2.8, 0.0, 0.0});
  ASSERT_EQ(SplitWarpedPanels(0.05, &grid), 1);
  EXPECT_EQ(diagonal(grid), (std::set<int>{1, 5}));
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
