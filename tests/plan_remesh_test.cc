// RemeshOverPlan (geometry/plan_remesh.h): the level-set stage's working mesh of a fine
// height-field reference. Known answers: every vertex on the reference, the rectangle's
// corners kept exactly, the area and the boundary loops the reference's, the edge length the
// one asked for, faces oriented as the reference's; and the references it must decline
// (too steep, facing both ways, folded over the plan).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/closest_point.h"
#include "geometry/plan_remesh.h"
#include "geometry/planar_domain_mesher.h"
#include "geometry/remesh.h"
#include "geometry/surface_generators.h"
#include "geometry/surface_model.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using GC = GreatCourtDimensions;

SurfaceModel FineGreatCourt() {
  GeneratorParams params;
  params.name = "great_court";
  params.edge_length = 0.8;  // ~44k triangles
  TriMesh mesh;
  EXPECT_TRUE(GenerateSurface(params, &mesh).ok());
  return SurfaceModel(std::move(mesh));
}

double Area(const TriMesh& mesh) {
  double area = 0.0;
  for (const auto f : mesh.faces()) area += mesh.calc_face_area(f);
  return area;
}

TEST(PlanRemesh, GreatCourtWorkingMeshLiesOnTheReferenceAndKeepsItsShape) {
  const SurfaceModel reference = FineGreatCourt();
  TriMesh working;
  std::string why_not;
  ASSERT_TRUE(RemeshOverPlan(reference, 1.2, 30.0, &working, &why_not)) << why_not;
  const SurfaceModel w(working);
  std::cout << "reference " << reference.num_faces() << " triangles → working " << w.num_faces()
            << ", mean edge " << MeanEdgeLength(working) << " m\n";
  // About as many triangles as CGAL's remeshing of the same reference gives (11.8k at 44k).
  EXPECT_GT(w.num_faces(), 10000);
  EXPECT_LT(w.num_faces(), 14000);
  EXPECT_NEAR(MeanEdgeLength(working), 1.2, 0.15);
  EXPECT_NEAR(Area(working), reference.total_area(), 1e-3 * reference.total_area());
  ASSERT_EQ(w.boundary_loops().size(), 2u);  // the rectangle and the Reading Room's ring
  // Every vertex on the reference: interior ones straight below or above where CGAL put them,
  // boundary ones on the reference's boundary.
  const ClosestPointQuery& query = reference.closest_points();
  double worst = 0.0;
  for (const auto v : working.vertices()) worst = std::max(worst, query.OnSurface(ToEigen(working.point(v))).distance);
  EXPECT_LT(worst, 1e-9);
  // The rectangle's four corners are vertices, exactly.
  for (const Eigen::Vector2d corner : {Eigen::Vector2d(-GC::b, -GC::d), Eigen::Vector2d(GC::b, -GC::d),
                                       Eigen::Vector2d(GC::b, GC::c), Eigen::Vector2d(-GC::b, GC::c)}) {
    double nearest = 1e9;
    for (const auto v : working.vertices()) nearest = std::min(nearest, (ToEigen(working.point(v)).head<2>() - corner).norm());
    EXPECT_LT(nearest, 1e-9) << corner.transpose();
  }
  for (int f = 0; f < w.num_faces(); ++f) ASSERT_GT(w.face_normal(f).z(), 0.0) << "face " << f;
}

TEST(PlanRemesh, ADownwardReferenceGivesADownwardWorkingMesh) {
  TriMesh up = testing::ToMesh(testing::GridSoup(40, [](double x, double y) { return 0.02 * (x * x - y * y); }));
  TriMesh down;
  for (const auto v : up.vertices()) down.add_vertex(up.point(v));
  for (const auto f : up.faces()) {
    std::vector<VertexHandle> ids(up.fv_begin(f), up.fv_end(f));
    down.add_face(ids[2], ids[1], ids[0]);
  }
  const SurfaceModel reference(std::move(down));
  TriMesh working;
  std::string why_not;
  ASSERT_TRUE(RemeshOverPlan(reference, 3.0, 30.0, &working, &why_not)) << why_not;
  const SurfaceModel w(working);
  EXPECT_GT(w.num_faces(), 200);
  EXPECT_NEAR(Area(working), reference.total_area(), 5e-3 * reference.total_area());  // a saddle's chords
  for (int f = 0; f < w.num_faces(); ++f) ASSERT_LT(w.face_normal(f).z(), 0.0) << "face " << f;
}

TEST(PlanRemesh, DeclinesAReferenceSteeperThanTheBound) {
  // Slope 10 (84°): n_z = 0.0995 < cos 80°.
  const SurfaceModel reference(testing::ToMesh(testing::GridSoup(20, [](double x, double) { return 10.0 * x; })));
  TriMesh working;
  std::string why_not;
  EXPECT_FALSE(RemeshOverPlan(reference, 2.0, 30.0, &working, &why_not));
  EXPECT_NE(why_not.find("steeper than 80°"), std::string::npos) << why_not;
  EXPECT_EQ(working.n_faces(), 0u);
  // Slope 5 (79°) is still a height field.
  const SurfaceModel steep(testing::ToMesh(testing::GridSoup(20, [](double x, double) { return 5.0 * x; })));
  EXPECT_TRUE(RemeshOverPlan(steep, 2.0, 30.0, &working, &why_not)) << why_not;
}

TEST(PlanRemesh, DeclinesARampThatWindsOverItself) {
  // A helicoid ramp, radii 5–10 m, 1.5 turns, rising 1 m per radian: every face gentle
  // (n_z ≥ 0.98) but the plan is covered twice.
  constexpr int kAround = 120, kAcross = 6;
  PolygonSoup soup;
  for (int i = 0; i <= kAround; ++i)
    for (int j = 0; j <= kAcross; ++j) {
      const double theta = 3.0 * M_PI * i / kAround, r = 5.0 + 5.0 * j / kAcross;
      soup.points.emplace_back(r * std::cos(theta), r * std::sin(theta), theta);
    }
  const auto id = [](int i, int j) { return i * (kAcross + 1) + j; };
  for (int i = 0; i < kAround; ++i)
    for (int j = 0; j < kAcross; ++j) {
      soup.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const SurfaceModel reference(testing::ToMesh(soup));
  TriMesh working;
  std::string why_not;
  EXPECT_FALSE(RemeshOverPlan(reference, 1.0, 30.0, &working, &why_not));
  EXPECT_FALSE(why_not.empty());
  std::cout << "ramp declined: " << why_not << "\n";
}

// A roof whose plan has a 10° corner (a wedge, fine reference from the same plan mesher):
// the plan mesher must end (CGAL's refinement leaves the small input angle alone).
TEST(PlanRemesh, EndsOnASharpCorner) {
  DomainLoop wedge;
  const double apex = 10.0 * M_PI / 180.0;
  wedge.polygon = {{0.0, 0.0}, {30.0, 0.0}, {30.0 * std::cos(apex), 30.0 * std::sin(apex)}};
  PlanarTriangulation plan;
  ASSERT_TRUE(MeshPlanarDomain({wedge}, 0.3, &plan).ok());
  PolygonSoup soup;
  for (const Eigen::Vector2d& p : plan.points) soup.points.emplace_back(p.x(), p.y(), 0.01 * p.squaredNorm());
  for (const auto& t : plan.triangles) soup.faces.push_back({t[0], t[1], t[2]});
  const SurfaceModel reference(testing::ToMesh(soup));
  TriMesh working;
  std::string why_not;
  ASSERT_TRUE(RemeshOverPlan(reference, 1.5, 5.0, &working, &why_not)) << why_not;
  double nearest = 1e9;
  for (const auto v : working.vertices()) nearest = std::min(nearest, ToEigen(working.point(v)).head<2>().norm());
  // CGAL's remeshing cuts the tip of so sharp a corner, here or on the reference itself
  // (RemeshIsotropic of the reference: 1.97 m, this path 2.59 m, at a 1.5 m edge; noted in
  // RESULTS.md, not fixed): the apex within two edges, the area within 1 %.
  EXPECT_LT(nearest, 3.0);
  EXPECT_NEAR(Area(working), reference.total_area(), 1e-2 * reference.total_area());
}

}  // namespace
}  // namespace pqlayout

namespace pqlayout {
namespace {

// CGAL 5.5's relaxation moved the constrained corners of a dome steep at its rim 0.35 m into
// the roof (CGAL issue #8388), and the extraction then split boundary chords without end
// (geometry/remesh.cc, RestoreCorners). Every corner of the reference stays a vertex, exactly.
TEST(RemeshIsotropic, KeepsTheCornersOfADomeSteepAtItsRim) {
  GeneratorParams params;
  params.name = "dome";
  params.width = 18.0;
  params.depth = 15.0;
  params.rise = 9.0;  // the rim rises at up to 50°
  params.edge_length = 1.0;
  TriMesh mesh;
  ASSERT_TRUE(GenerateSurface(params, &mesh).ok());
  const SurfaceModel reference(std::move(mesh));
  const std::vector<int> corners = reference.BoundaryCorners(30.0 * M_PI / 180.0);
  ASSERT_EQ(corners.size(), 4u);
  TriMesh working;
  ASSERT_TRUE(RemeshIsotropic(reference, 1.2, 30.0, 3, &working).ok());
  for (const int c : corners) {
    double nearest = 1e9;
    for (const auto v : working.vertices())
      nearest = std::min(nearest, (ToEigen(working.point(v)) - reference.position(c)).norm());
    EXPECT_EQ(nearest, 0.0) << "corner at " << reference.position(c).transpose();
  }
  EXPECT_EQ(SurfaceModel(std::move(working)).BoundaryCorners(30.0 * M_PI / 180.0).size(), 4u);
}

}  // namespace
}  // namespace pqlayout
