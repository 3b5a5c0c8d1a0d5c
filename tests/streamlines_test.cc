// Evenly spaced streamlines (straight, radial and sign-flipped line fields) and level lines of
// P1 functions (straight lines on a grid, ties at vertices, ridges and valleys, closed loops
// on a disk): the curves the figures draw (tests/svg_figures_test.cc draws them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "geometry/level_lines.h"
#include "geometry/streamlines.h"
#include "geometry/surface_generators.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using testing::Centroid;
using Polylines = std::vector<std::vector<Vector2d>>;

double Cross2(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

double MinDistanceBetweenLines(const Polylines& lines) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < lines.size(); ++a)
    for (size_t b = a + 1; b < lines.size(); ++b)
      for (const auto& p : lines[a])
        for (const auto& q : lines[b]) best = std::min(best, (p - q).norm());
  return best;
}

TEST(Streamlines, ConstantFieldGivesEvenlySpacedHorizontalLines) {
  const double side = 20.0;
  const SurfaceModel square(testing::ToMesh(testing::FlatGridSoup(static_cast<int>(side))));
  StreamlineOptions options;
  options.separation = 1.3;
  const Polylines lines = EvenlySpacedStreamlines(
      square, std::vector<Vector3d>(square.num_faces(), Vector3d::UnitX()), options);

  EXPECT_NEAR(static_cast<double>(lines.size()), side / options.separation, 1.0);
  std::vector<double> heights;
  for (const auto& line : lines) {
    ASSERT_GE(line.size(), 2u);
    for (const auto& p : line) EXPECT_NEAR(p.y(), line.front().y(), 1e-9);
    const auto [left, right] = std::minmax(line.front().x(), line.back().x());
    EXPECT_NEAR(left, 0.0, 1e-6);  // clipped onto the boundary at both ends
    EXPECT_NEAR(right, side, 1e-6);
    heights.push_back(line.front().y());
  }
  std::sort(heights.begin(), heights.end());
  for (size_t i = 1; i < heights.size(); ++i)
    EXPECT_GE(heights[i] - heights[i - 1], options.test_ratio * options.separation);
  EXPECT_LE(heights.front(), options.separation);
  EXPECT_GE(heights.back(), side - options.separation);
}

TEST(Streamlines, RadialFieldOnDiskGivesRadialLines) {
  const double edge_length = 0.25;
  const SurfaceModel surface(testing::GeneratedMesh("disk", 20.0, 0.0, 0.0, edge_length));
  std::vector<Vector3d> radial(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) radial[f] << Centroid(surface, f).normalized(), 0.0;
  StreamlineOptions options;
  options.separation = 1.0;
  const Polylines lines = EvenlySpacedStreamlines(surface, radial, options);

  ASSERT_GE(lines.size(), 20u);
  // Collinear with the centre: every point is close to the line through the centre and the
  // farthest point (the field is constant per face, so up to a fraction of an edge).
  double deviation = 0.0;
  for (const auto& line : lines) {
    const auto farthest = std::max_element(
        line.begin(), line.end(),
        [](const Vector2d& a, const Vector2d& b) { return a.squaredNorm() < b.squaredNorm(); });
    const Vector2d u = farthest->normalized();
    for (const auto& p : line)
      deviation = std::max(deviation, std::abs(u.x() * p.y() - u.y() * p.x()));
  }
  EXPECT_LT(deviation, 0.1 * edge_length);
  EXPECT_GE(MinDistanceBetweenLines(lines), options.test_ratio * options.separation * (1 - 1e-9));
}

// The singularities a caller has found already (the guidance stage's) are the ones used: the
// same list gives the same lines to the bit, and a list without the radial field's centre
// (index +1) lets lines run into the faces round it, which are otherwise no-field.
TEST(Streamlines, SingularitiesGivenAreTheOnesUsed) {
  const SurfaceModel surface(testing::GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.5));
  std::vector<Vector3d> radial(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) radial[f] << Centroid(surface, f).normalized(), 0.0;
  const std::vector<LineFieldSingularity> found = FindLineFieldSingularities(surface, radial);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].index, 1.0);
  StreamlineOptions options;
  options.separation = 1.0;
  const Polylines own = EvenlySpacedStreamlines(surface, radial, options);
  options.singularities = &found;
  EXPECT_EQ(EvenlySpacedStreamlines(surface, radial, options), own);
  const std::vector<LineFieldSingularity> none;
  options.singularities = &none;
  const auto closest_to_centre = [](const Polylines& lines) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& line : lines)
      for (const auto& p : line) best = std::min(best, p.norm());
    return best;
  };
  EXPECT_LT(closest_to_centre(EvenlySpacedStreamlines(surface, radial, options)), 0.5 * closest_to_centre(own));
}

TEST(Streamlines, SignFlipsPerFaceDoNotChangeTheLines) {
  const SurfaceModel square(testing::ToMesh(testing::FlatGridSoup(16)));
  std::vector<Vector3d> field(square.num_faces()), flipped(square.num_faces());
  std::mt19937 random(7);
  for (int f = 0; f < square.num_faces(); ++f) {
    const Vector2d c = Centroid(square, f);
    const double angle = 0.15 * c.x() + 0.1 * c.y() * c.y() / 16.0;
    field[f] = Vector3d(std::cos(angle), std::sin(angle), 0.0);
    flipped[f] = (random() % 2 == 0) ? field[f] : Vector3d(-field[f]);
  }
  StreamlineOptions options;
  options.separation = 1.0;
  const Polylines reference = EvenlySpacedStreamlines(square, field, options);
  const Polylines with_flips = EvenlySpacedStreamlines(square, flipped, options);
  ASSERT_GE(reference.size(), 10u);
  ASSERT_EQ(reference.size(), with_flips.size());
  for (size_t i = 0; i < reference.size(); ++i) {
    ASSERT_EQ(reference[i].size(), with_flips[i].size());
    for (size_t k = 0; k < reference[i].size(); ++k) EXPECT_EQ(reference[i][k], with_flips[i][k]);
  }
}

TEST(Streamlines, VerticalFacesAndSizeMismatchGiveNoLines) {
  // z = 1e9·x: every face is (nearly) vertical in the top view.
  const SurfaceModel wall(
      testing::ToMesh(testing::GridSoup(4, [](double x, double) { return 1e9 * x; })));
  StreamlineOptions options;
  options.separation = 0.5;
  EXPECT_TRUE(EvenlySpacedStreamlines(
                  wall, std::vector<Vector3d>(wall.num_faces(), Vector3d::UnitY()), options)
                  .empty());
  EXPECT_TRUE(
      EvenlySpacedStreamlines(wall, std::vector<Vector3d>(3, Vector3d::UnitY()), options).empty());
}

using Lines3 = std::vector<std::vector<Vector3d>>;

std::vector<double> VertexValues(const SurfaceModel& s, double (*u)(const Vector3d&)) {
  std::vector<double> values(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v) values[v] = u(s.position(v));
  return values;
}

struct GridLevels {
  int n;     // side of the square, in unit cells
  double h;  // level spacing, divides n
};

class LevelLinesOnFlatSquare : public ::testing::TestWithParam<GridLevels> {};

// φ = x/h, ψ = y/h: the level lines φ = i, ψ = j are the straight lines x = i·h, y = j·h
// across the square, running along n × ∇u (n = +z): φ's towards +y, ψ's towards -x.
TEST_P(LevelLinesOnFlatSquare, AreTheStraightLinesEveryH) {
  const auto [n, h] = GetParam();
  const SurfaceModel square(testing::ToMesh(testing::FlatGridSoup(n)));
  std::vector<double> phi(square.num_vertices()), psi(square.num_vertices());
  for (int v = 0; v < square.num_vertices(); ++v) {
    phi[v] = square.position(v).x() / h;
    psi[v] = square.position(v).y() / h;
  }
  const int levels = static_cast<int>(std::lround(n / h));
  for (int i = 1; i < levels; ++i)
    for (const int axis : {0, 1}) {
      const Lines3 lines = LevelLines(square, axis == 0 ? phi : psi, i);
      ASSERT_EQ(lines.size(), 1u) << "axis " << axis << " level " << i;
      const auto& line = lines.front();
      ASSERT_GE(line.size(), static_cast<size_t>(n + 1));
      double lo = n, hi = 0.0;
      for (const Vector3d& p : line) {
        EXPECT_NEAR(p[axis], i * h, 1e-9);
        lo = std::min(lo, p[1 - axis]);
        hi = std::max(hi, p[1 - axis]);
      }
      EXPECT_NEAR(lo, 0.0, 1e-9);  // spans the square
      EXPECT_NEAR(hi, n, 1e-9);
      // φ along z × x = +y, ψ along z × y = -x.
      const Vector3d run = line.back() - line.front();
      EXPECT_NEAR(axis == 0 ? run.y() : -run.x(), n, 1e-9);
      for (size_t k = 1; k < line.size(); ++k)  // no back-tracking, no doubled segment
        EXPECT_GT(axis == 0 ? line[k].y() - line[k - 1].y() : line[k - 1].x() - line[k].x(),
                  -1e-12);
    }
  // Ties count as above: the level at the minimum (x = 0) has no line, the one at the
  // maximum (x = n) runs along the boundary.
  EXPECT_TRUE(LevelLines(square, phi, 0.0).empty());
  const Lines3 at_max = LevelLines(square, phi, levels);
  ASSERT_EQ(at_max.size(), 1u);
  for (const Vector3d& p : at_max.front()) EXPECT_NEAR(p.x(), n, 1e-9);
  EXPECT_TRUE(LevelLines(square, phi, levels + 1).empty());
  EXPECT_TRUE(LevelLines(square, phi, -1.0).empty());
}

INSTANTIATE_TEST_SUITE_P(VertexAndEdgeCrossings, LevelLinesOnFlatSquare,
                         ::testing::Values(GridLevels{12, 3.0},    // levels through vertices
                                           GridLevels{10, 2.5},    // alternately inside edges
                                           GridLevels{7, 7.0 / 3.0}));  // never at a vertex

// Levels passing exactly through vertices, along mesh edges with the function rising across
// (one face on each side crossed), along a ridge (both faces below: the same edge twice)
// and in a valley (nothing below): one line, one line, one line, none.
TEST(LevelLines, LevelsThroughVerticesAndAlongEdgesGiveOneLine) {
  const int n = 8;
  const SurfaceModel square(testing::ToMesh(testing::FlatGridSoup(n)));
  const auto expect_one_line = [&](const std::vector<double>& u, double c, const Vector3d& from,
                                   const Vector3d& to, size_t points) {
    const Lines3 lines = LevelLines(square, u, c);
    ASSERT_EQ(lines.size(), 1u) << "level " << c;
    const auto& line = lines.front();
    EXPECT_EQ(line.size(), points) << "level " << c;
    const bool forward = (line.front() - from).norm() < 1e-9;
    EXPECT_TRUE(forward || (line.front() - to).norm() < 1e-9) << line.front().transpose();
    EXPECT_LT((line.back() - (forward ? to : from)).norm(), 1e-9) << line.back().transpose();
    for (const Vector3d& p : line)  // on the straight line from → to
      EXPECT_NEAR((p - from).cross(to - from).norm(), 0.0, 1e-9);
  };
  // x + y = 5: through the vertices (i, 5 - i) and the midpoints of the cells' diagonals.
  const auto sum = VertexValues(square, [](const Vector3d& p) { return p.x() + p.y(); });
  expect_one_line(sum, 5.0, {0, 5, 0}, {5, 0, 0}, 11);
  // x − y = 0 along the diagonal edges of the cells.
  const auto difference = VertexValues(square, [](const Vector3d& p) { return p.x() - p.y(); });
  expect_one_line(difference, 0.0, {0, 0, 0}, {n, n, 0}, n + 1);
  // −|x − y| (ridge at 0): kept once; |x − y| (valley at 0): nothing is below.
  const auto ridge =
      VertexValues(square, [](const Vector3d& p) { return -std::abs(p.x() - p.y()); });
  expect_one_line(ridge, 0.0, {0, 0, 0}, {n, n, 0}, n + 1);
  const auto valley =
      VertexValues(square, [](const Vector3d& p) { return std::abs(p.x() - p.y()); });
  EXPECT_TRUE(LevelLines(square, valley, 0.0).empty());
  // A single vertex at the level (a peak exactly at c) gives no line, nor does bad input.
  std::vector<double> peak(square.num_vertices(), 0.0);
  peak[4 * (n + 1) + 4] = 1.0;
  EXPECT_TRUE(LevelLines(square, peak, 1.0).empty());
  EXPECT_TRUE(LevelLines(square, std::vector<double>(3, 0.0), 0.0).empty());
  EXPECT_TRUE(LevelLines(square, sum, std::nan("")).empty());
}

// φ = r/h on a disk: the level lines are closed loops (first point == last point) of radius
// i·h up to the P1 interpolation error, counter-clockwise (along n × ∇r, n = +z).
TEST(LevelLines, RadialFunctionOnDiskGivesClosedCircles) {
  const SurfaceModel surface(testing::GeneratedMesh("disk", 20.0, 0.0, 0.0, 0.5));
  const double h = 2.0;
  double longest_edge = 0.0;
  for (const auto e : surface.mesh().edges())
    longest_edge = std::max(longest_edge, surface.mesh().calc_edge_length(e));
  std::vector<double> phi(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v)
    phi[v] = surface.position(v).head<2>().norm() / h;
  for (int i = 1; i <= 4; ++i) {
    const double r = i * h;
    const Lines3 lines = LevelLines(surface, phi, i);
    ASSERT_EQ(lines.size(), 1u) << "r = " << r;
    const auto& loop = lines.front();
    ASSERT_GE(loop.size(), 8u);
    EXPECT_EQ(loop.front(), loop.back());  // closed: the first point repeated exactly
    // Linear interpolation of r along an edge of length ℓ overestimates it by at most
    // ℓ² / (8 r_min): the crossing points lie on or just inside the circle.
    const double tolerance = longest_edge * longest_edge / (8.0 * (r - longest_edge));
    double twice_area = 0.0, length = 0.0;
    for (size_t k = 0; k < loop.size(); ++k) {
      const double radius = loop[k].head<2>().norm();
      EXPECT_LE(radius, r + 1e-9);
      EXPECT_GE(radius, r - tolerance);
      if (k == 0) continue;
      twice_area += Cross2(loop[k - 1].head<2>(), loop[k].head<2>());
      length += (loop[k] - loop[k - 1]).norm();
    }
    EXPECT_NEAR(length, 2.0 * M_PI * r, 0.02 * r);
    EXPECT_GT(twice_area, 0.0);  // counter-clockwise
  }
}

}  // namespace
}  // namespace pqlayout
