// Built-in surfaces and the planar domain mesher: the Great Court formula against the values
// stated in SPEC.md, and every generated mesh against its analytic surface (heights at the
// vertices, exact boundary, area, triangle shape measured in space, orientation, topology).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/mesh.h"
#include "geometry/planar_domain_mesher.h"
#include "base/status.h"
#include "geometry/surface_generators.h"
#include "tests/generator_measures.h"

namespace pqlayout {
namespace {

using GC = GreatCourtDimensions;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Area of the graph of f over [-w/2, w/2] x [-d/2, d/2] by the midpoint rule on the area
// element √(1 + |∇f|²), given the gradient.
double GraphArea(double width, double depth,
                 const std::function<Eigen::Vector2d(double, double)>& gradient) {
  constexpr int kCells = 1000;
  const double dx = width / kCells, dy = depth / kCells;
  double area = 0.0;
  for (int i = 0; i < kCells; ++i) {
    for (int j = 0; j < kCells; ++j) {
      const Eigen::Vector2d g =
          gradient(-0.5 * width + (i + 0.5) * dx, -0.5 * depth + (j + 0.5) * dy);
      area += std::sqrt(1.0 + g.squaredNorm()) * dx * dy;
    }
  }
  return area;
}

// ---------------------------------------------------------------------------------------
// GreatCourtHeight against SPEC.md.

TEST(GreatCourtHeight, IsHCenOnTheRing) {
  for (int k = 0; k < 36; ++k) {
    const double theta = 2.0 * M_PI * k / 36;
    EXPECT_NEAR(GreatCourtHeight(GC::a * std::cos(theta), GC::a * std::sin(theta)), 20.955, 1e-9)
        << "theta " << theta;
  }
}

TEST(GreatCourtHeight, IsHEdgeOnTheRectangleAndAtItsCorners) {
  constexpr int kSteps = 50;
  for (int k = 0; k <= kSteps; ++k) {
    const double s = static_cast<double>(k) / kSteps;
    const double x = -GC::b + s * 2.0 * GC::b, y = -GC::d + s * (GC::c + GC::d);
    EXPECT_NEAR(GreatCourtHeight(x, -GC::d), 19.71, 1e-9) << "south x " << x;
    EXPECT_NEAR(GreatCourtHeight(x, GC::c), 19.71, 1e-9) << "north x " << x;
    EXPECT_NEAR(GreatCourtHeight(-GC::b, y), 19.71, 1e-9) << "west y " << y;
    EXPECT_NEAR(GreatCourtHeight(GC::b, y), 19.71, 1e-9) << "east y " << y;
  }
  for (double x : {-GC::b, GC::b}) {
    for (double y : {-GC::d, GC::c}) EXPECT_NEAR(GreatCourtHeight(x, y), 19.71, 1e-9);
  }
}

TEST(GreatCourtHeight, MatchesTheSpecCheckPoints) {
  EXPECT_NEAR(GreatCourtHeight(0.0, 34.135), 26.157, 0.01);
  EXPECT_NEAR(GreatCourtHeight(0.0, -36.685), 27.573, 0.01);
}

TEST(GreatCourtHeight, IsFiniteOnTheClosedDomain) {
  constexpr int kSteps = 400;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j <= kSteps; ++j) {
      // The last grid line is set exactly onto the rectangle edge.
      const double x = i == kSteps ? GC::b : -GC::b + 2.0 * GC::b * i / kSteps;
      const double y = j == kSteps ? GC::c : -GC::d + (GC::c + GC::d) * j / kSteps;
      if (std::hypot(x, y) < GC::a) continue;
      ASSERT_TRUE(std::isfinite(GreatCourtHeight(x, y))) << x << ", " << y;
    }
  }
}

// ---------------------------------------------------------------------------------------
// The great_court mesh.

class GreatCourtMesh : public ::testing::TestWithParam<double> {};

TEST_P(GreatCourtMesh, HasGoodTrianglesInSpace) {
  const double edge_length = GetParam();
  const TriMesh mesh = Generate(Params("great_court", edge_length));
  const MeshMeasures m = Measure(mesh);
  EXPECT_GE(m.min_angle, 20.0 * kDegree) << m.min_angle / kDegree;
  EXPECT_LE(m.max_edge, 1.5 * edge_length);
  EXPECT_GT(m.min_normal_z, 0.0);
  EXPECT_LT(MaxHeightError(mesh, GreatCourtHeight), 1e-12);
  EXPECT_EQ(CountBoundaryLoops(mesh), 2);
  EXPECT_EQ(EulerCharacteristic(mesh), 0);
}

// 0.3 m and 0.17 m: 309k and 962k triangles, whose plans are seeded with a lattice
// (planar_domain_mesher.h); with the lattice points 0.75 instead of 1 edge from the boundary,
// the steep north edge's triangles came out at 18.3° in space at 0.17 m.
INSTANTIATE_TEST_SUITE_P(EdgeLengths, GreatCourtMesh, ::testing::Values(2.0, 1.0, 0.7, 0.3, 0.17));

TEST(GreatCourt, AreaIsAbout6180SquareMetres) {
  const MeshMeasures m = Measure(Generate(Params("great_court")));
  EXPECT_NEAR(m.area, 6180.0, 0.005 * 6180.0);
}

TEST(GreatCourt, BoundaryIsExactlyOnTheRingAndTheRectangle) {
  const TriMesh mesh = Generate(Params("great_court"));
  int ring = 0, rectangle = 0;
  for (VertexHandle v : mesh.vertices()) {
    if (!mesh.is_boundary(v)) continue;
    const OpenMesh::Vec3d& p = mesh.point(v);
    if (std::hypot(p[0], p[1]) < 0.5 * (GC::a + GC::b)) {
      ++ring;
      EXPECT_NEAR(std::hypot(p[0], p[1]), GC::a, 1e-9);
      EXPECT_NEAR(p[2], GC::h_cen, 1e-9);
    } else {
      ++rectangle;
      EXPECT_TRUE(std::abs(p[0]) == GC::b || p[1] == GC::c || p[1] == -GC::d)
          << p[0] << ", " << p[1];
      EXPECT_NEAR(p[2], GC::h_edge, 1e-12);
    }
  }
  EXPECT_GE(ring, static_cast<int>(2.0 * M_PI * GC::a));  // at most 1 m apart
  EXPECT_GE(rectangle, static_cast<int>(4.0 * GC::b + 2.0 * (GC::c + GC::d)));
  for (double x : {-GC::b, GC::b}) {
    for (double y : {-GC::d, GC::c}) EXPECT_TRUE(HasVertexAt(mesh, x, y)) << x << ", " << y;
  }
}

// ---------------------------------------------------------------------------------------
// dome, hypar, barrel, plane over the default 30 m x 30 m rectangle with 5 m rise.

struct RectangleCase {
  std::string name;
  std::function<double(double, double)> height;
  std::function<Eigen::Vector2d(double, double)> gradient;
};

// Defaults: width = depth = 30, rise = 5.
std::vector<RectangleCase> RectangleCases() {
  const double half = 15.0, rise = 5.0;
  const double barrel_radius = (half * half + rise * rise) / (2.0 * rise);  // 25 m
  return {
      {"dome",
       [=](double x, double y) { return rise * (1.0 - 0.5 * (x * x + y * y) / (half * half)); },
       [=](double x, double y) -> Eigen::Vector2d {
         return Eigen::Vector2d(-rise * x, -rise * y) / (half * half);
       }},
      {"hypar", [=](double x, double y) { return rise * x * y / (half * half); },
       [=](double x, double y) -> Eigen::Vector2d {
         return Eigen::Vector2d(y, x) * rise / (half * half);
       }},
      {"barrel",
       [=](double x, double) {
         return std::sqrt(barrel_radius * barrel_radius - x * x) - (barrel_radius - rise);
       },
       [=](double x, double) {
         return Eigen::Vector2d(-x / std::sqrt(barrel_radius * barrel_radius - x * x), 0.0);
       }},
      {"plane", [](double, double) { return 0.0; },
       [](double, double) { return Eigen::Vector2d::Zero(); }},
  };
}

TEST(RectangleSurfaces, MatchTheirAnalyticSurface) {
  for (const RectangleCase& c : RectangleCases()) {
    SCOPED_TRACE(c.name);
    const TriMesh mesh = Generate(Params(c.name));
    const MeshMeasures m = Measure(mesh);
    EXPECT_LT(MaxHeightError(mesh, c.height), 1e-12);
    for (double x : {-15.0, 15.0}) {
      for (double y : {-15.0, 15.0}) EXPECT_TRUE(HasVertexAt(mesh, x, y)) << x << ", " << y;
    }
    EXPECT_GE(m.min_angle, 20.0 * kDegree) << m.min_angle / kDegree;
    EXPECT_LE(m.max_edge, 1.5);
    EXPECT_GT(m.min_normal_z, 0.0);
    EXPECT_EQ(CountBoundaryLoops(mesh), 1);
    EXPECT_EQ(EulerCharacteristic(mesh), 1);
    // Piecewise-linear interpolation of the surface: area error O(h²) with h = 1 m on a
    // 30 m span.
    const double area = GraphArea(30.0, 30.0, c.gradient);
    EXPECT_NEAR(m.area, area, 2e-4 * area);
  }
}

TEST(RectangleSurfaces, AnalyticValuesOfTheReferenceAreas) {
  // The quadrature itself, against closed forms: the plane and the barrel (arc length 2R
  // asin(w / 2R) times the depth).
  EXPECT_NEAR(GraphArea(30.0, 30.0, RectangleCases()[3].gradient), 900.0, 1e-6);
  EXPECT_NEAR(GraphArea(30.0, 30.0, RectangleCases()[2].gradient),
              30.0 * 2.0 * 25.0 * std::asin(0.6), 1e-3);
}

TEST(RectangleSurfaces, PlaneAreaIsExact) {
  EXPECT_NEAR(Measure(Generate(Params("plane"))).area, 900.0, 1e-9);
}

TEST(RectangleSurfaces, ReferenceHeightsAreTheSpecifiedOnes) {
  // Dome: apex at the rise, corners at 0; hypar: corners at ±rise; barrel: crown at the rise,
  // supports at 0 along the whole x = ±w/2 edges.
  const std::vector<RectangleCase> cases = RectangleCases();
  EXPECT_NEAR(cases[0].height(0.0, 0.0), 5.0, 1e-12);
  EXPECT_NEAR(cases[0].height(15.0, -15.0), 0.0, 1e-12);
  EXPECT_NEAR(cases[1].height(15.0, 15.0), 5.0, 1e-12);
  EXPECT_NEAR(cases[1].height(15.0, -15.0), -5.0, 1e-12);
  EXPECT_NEAR(cases[2].height(0.0, 7.0), 5.0, 1e-12);
  EXPECT_NEAR(cases[2].height(-15.0, 7.0), 0.0, 1e-12);
  const TriMesh barrel = Generate(Params("barrel"));
  int supports = 0;
  for (VertexHandle v : barrel.vertices()) {
    if (std::abs(barrel.point(v)[0]) != 15.0) continue;
    ++supports;
    EXPECT_NEAR(barrel.point(v)[2], 0.0, 1e-12);
  }
  EXPECT_GE(supports, 2 * 31);
}

// ---------------------------------------------------------------------------------------
// disk and annulus.

// Boundary vertices must be exactly on their circle; the area is π(r_o² - r_i²) up to the
// circular segments cut off by chords no longer than the edge length h, each about L³/(12 r)
// for a chord L, so at most π h²/6 per circle.
void ExpectFlatRoundDomain(const TriMesh& mesh, double outer, double inner, double h) {
  for (VertexHandle v : mesh.vertices()) {
    const OpenMesh::Vec3d& p = mesh.point(v);
    EXPECT_EQ(p[2], 0.0);
    if (!mesh.is_boundary(v)) continue;
    const double r = std::hypot(p[0], p[1]);
    EXPECT_NEAR(r, r > 0.5 * (outer + inner) ? outer : inner, 1e-12);
  }
  const MeshMeasures m = Measure(mesh);
  const double area = M_PI * (outer * outer - inner * inner);
  // Chords of the outer circle lose area, chords of the inner circle (a hole) add area.
  const double chord_segments = M_PI * h * h / 6.0;
  EXPECT_GE(m.area, area - chord_segments);
  EXPECT_LE(m.area, area + (inner > 0.0 ? chord_segments : 1e-9));
  EXPECT_GE(m.min_angle, 20.0 * kDegree);
  EXPECT_GT(m.min_normal_z, 0.0);
}

TEST(RoundSurfaces, DiskIsExactOnItsCircle) {
  GeneratorParams params = Params("disk");
  params.width = 20.0;
  const TriMesh mesh = Generate(params);
  ExpectFlatRoundDomain(mesh, 10.0, 0.0, 1.0);
  EXPECT_EQ(CountBoundaryLoops(mesh), 1);
  EXPECT_EQ(EulerCharacteristic(mesh), 1);
}

TEST(RoundSurfaces, AnnulusIsExactOnBothCircles) {
  GeneratorParams params = Params("annulus", 0.5);
  params.width = 20.0;
  params.depth = 8.0;
  const TriMesh mesh = Generate(params);
  ExpectFlatRoundDomain(mesh, 10.0, 4.0, 0.5);
  EXPECT_EQ(CountBoundaryLoops(mesh), 2);
  EXPECT_EQ(EulerCharacteristic(mesh), 0);
}

// ---------------------------------------------------------------------------------------
// Bad parameters.

void ExpectInvalid(const GeneratorParams& params, const std::string& key) {
  TriMesh mesh;
  const Status status = GenerateSurface(params, &mesh);
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput) << params.name;
  EXPECT_NE(status.message().find(key), std::string::npos) << status.message();
}

TEST(GenerateSurface, RefusesBadParametersNamingTheKey) {
  ExpectInvalid(Params("torus"), "surface.generator");
  for (double bad : {0.0, -1.0, kNaN, kInfinity}) {
    ExpectInvalid(Params("great_court", bad), "surface.edge_length");
    ExpectInvalid(Params("plane", bad), "surface.edge_length");
  }
  ExpectInvalid(Params("great_court", 1e-3), "surface.edge_length");  // ~3e10 triangles
  GeneratorParams params = Params("dome");
  params.width = -30.0;
  ExpectInvalid(params, "surface.width");
  params = Params("hypar");
  params.depth = kNaN;
  ExpectInvalid(params, "surface.depth");
  params = Params("barrel");
  params.rise = 0.0;
  ExpectInvalid(params, "surface.rise");
  params.rise = 15.0;  // half the width: the arc is no longer a height field
  ExpectInvalid(params, "surface.rise");
  params = Params("annulus");
  params.depth = params.width;
  ExpectInvalid(params, "surface.depth");
}

TEST(GenerateSurface, ListsEveryGenerator) {
  const std::vector<std::string> expected = {"great_court", "dome",         "hypar",           "barrel",
                                             "disk",        "annulus",      "plane",           "dome_circular",
                                             "saddle_elliptic", "canopy",   "l_shape",         "hole_offcentre",
                                             "two_holes",   "wavy"};
  std::vector<std::string> names = GeneratorNames();
  EXPECT_EQ(names, expected);
  for (const std::string& name : names) {
    GeneratorParams params = Params(name, 2.0);
    params.depth = 10.0;  // the annulus needs an inner diameter below the outer one
    TriMesh mesh;
    EXPECT_TRUE(GenerateSurface(params, &mesh).ok()) << name;
  }
}

// ---------------------------------------------------------------------------------------
// MeshPlanarDomain on its own: a non-convex outer loop with a square hole.

double Cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

TEST(MeshPlanarDomain, MeshesANonConvexDomainWithAHole) {
  DomainLoop outer, hole;
  outer.polygon = {{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}};  // L shape, area 64
  hole.polygon = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};                       // area 4
  const double h = 0.7;
  PlanarTriangulation plan;
  ASSERT_TRUE(MeshPlanarDomain({outer, hole}, h, &plan).ok());

  for (const DomainLoop& loop : {outer, hole}) {
    for (const Eigen::Vector2d& corner : loop.polygon) {
      EXPECT_NE(std::find(plan.points.begin(), plan.points.end(), corner), plan.points.end())
          << corner.transpose();
    }
  }
  std::vector<bool> used(plan.points.size(), false);
  double area = 0.0, min_angle = M_PI, max_edge = 0.0;
  for (const std::array<int, 3>& t : plan.triangles) {
    const Eigen::Vector2d p[3] = {plan.points[t[0]], plan.points[t[1]], plan.points[t[2]]};
    const double twice_area = Cross(p[1] - p[0], p[2] - p[0]);
    EXPECT_GT(twice_area, 0.0);  // counter-clockwise
    area += 0.5 * twice_area;
    const Eigen::Vector2d centroid = (p[0] + p[1] + p[2]) / 3.0;
    EXPECT_FALSE(centroid.x() > 4 && centroid.y() > 4) << "outside the L";
    EXPECT_FALSE(centroid.x() > 1 && centroid.x() < 3 && centroid.y() > 1 && centroid.y() < 3)
        << "inside the hole";
    for (int k = 0; k < 3; ++k) {
      used[t[k]] = true;
      const Eigen::Vector2d u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
      min_angle = std::min(min_angle, std::atan2(std::abs(Cross(u, v)), u.dot(v)));
      max_edge = std::max(max_edge, u.norm());
    }
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool b) { return b; }));
  EXPECT_NEAR(area, 60.0, 1e-9);
  EXPECT_GE(min_angle, 20.0 * kDegree);
  EXPECT_LE(max_edge, h * (1.0 + 1e-12));
}

TEST(MeshPlanarDomain, CircleLoopIsFineEnoughAndSnapped) {
  const DomainLoop circle = CircleLoop({1.0, 2.0}, 3.0, 0.4);
  for (size_t i = 0; i < circle.polygon.size(); ++i) {
    EXPECT_LE((circle.polygon[i] - circle.polygon[(i + 1) % circle.polygon.size()]).norm(), 0.4);
  }
  PlanarTriangulation plan;
  ASSERT_TRUE(MeshPlanarDomain({circle}, 0.4, &plan).ok());
  int on_circle = 0;
  for (const Eigen::Vector2d& p : plan.points) {
    const double r = (p - circle.center).norm();
    EXPECT_LE(r, 3.0 + 1e-12);
    on_circle += std::abs(r - 3.0) < 1e-12;
  }
  EXPECT_GE(on_circle, static_cast<int>(circle.polygon.size()));
}

TEST(MeshPlanarDomain, RefusesBadInput) {
  DomainLoop square;
  square.polygon = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  DomainLoop segment;
  segment.polygon = {{0, 0}, {1, 0}};
  DomainLoop closed_explicitly = square;
  closed_explicitly.polygon.push_back(square.polygon.front());
  DomainLoop not_finite = square;
  not_finite.polygon[2].x() = kNaN;
  PlanarTriangulation plan;
  for (double bad : {0.0, -0.1, kNaN, kInfinity}) {
    EXPECT_EQ(MeshPlanarDomain({square}, bad, &plan).code(), StatusCode::kInvalidInput);
  }
  EXPECT_EQ(MeshPlanarDomain({}, 0.1, &plan).code(), StatusCode::kInvalidInput);
  EXPECT_EQ(MeshPlanarDomain({segment}, 0.1, &plan).code(), StatusCode::kInvalidInput);
  EXPECT_EQ(MeshPlanarDomain({not_finite}, 0.1, &plan).code(), StatusCode::kInvalidInput);
  EXPECT_EQ(MeshPlanarDomain({closed_explicitly}, 0.1, &plan).code(), StatusCode::kInvalidInput);
  EXPECT_EQ(MeshPlanarDomain({square}, 1e-5, &plan).code(), StatusCode::kInvalidInput);
}

}  // namespace
}  // namespace pqlayout
