// MeshPlanarDomain (geometry/planar_domain_mesher.h) on a domain large enough in triangles for
// the lattice seeding (above 200k expected): the refinement's guarantees still hold, the
// boundary is kept exactly, and the interior is the lattice (equilateral triangles).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/planar_domain_mesher.h"

namespace pqlayout {
namespace {

struct Angles {
  double smallest = M_PI;        // over every triangle
  double longest_edge = 0.0;
  std::vector<double> minima;    // each triangle's smallest angle
};

Angles MeasureAngles(const PlanarTriangulation& t) {
  Angles a;
  for (const auto& tri : t.triangles) {
    double smallest = M_PI;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d p = t.points[tri[k]], u = t.points[tri[(k + 1) % 3]] - p, v = t.points[tri[(k + 2) % 3]] - p;
      smallest = std::min(smallest, std::acos(std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0)));
      a.longest_edge = std::max(a.longest_edge, u.norm());
    }
    a.smallest = std::min(a.smallest, smallest);
    a.minima.push_back(smallest);
  }
  return a;
}

TEST(PlanarDomainMesher, ALargeDomainIsSeededWithALatticeAndKeepsTheRefinementsBounds) {
  const double edge = 0.045;  // 5 × 96.9 m² / edge² ≈ 239k triangles expected: above 200k
  DomainLoop square;
  square.polygon = {{0.0, 0.0}, {10.0, 0.0}, {10.0, 10.0}, {0.0, 10.0}};
  const DomainLoop hole = CircleLoop({6.0, 4.0}, 1.0, edge);
  PlanarTriangulation t;
  ASSERT_TRUE(MeshPlanarDomain({square, hole}, edge, &t).ok());
  const Angles a = MeasureAngles(t);
  EXPECT_GE(a.smallest, std::asin(std::sqrt(0.125)) - 1e-9);  // the refinement's shape bound, 20.7°
  EXPECT_LE(a.longest_edge, edge * (1.0 + 1e-9));               // its size bound
  // The interior is the lattice: most triangles equilateral (the refinement alone gives a
  // median smallest angle of 46° here, in 1.2 s instead of 0.25 s).
  std::vector<double> minima = a.minima;
  std::nth_element(minima.begin(), minima.begin() + minima.size() / 2, minima.end());
  EXPECT_GT(minima[minima.size() / 2], 59.0 * M_PI / 180.0);
  // As many triangles as a lattice of 0.68 edge over the area, within the boundary band.
  const double area = 100.0 - M_PI;
  const double lattice = area / (std::sqrt(3.0) / 4.0 * std::pow(0.68 * edge, 2));
  EXPECT_NEAR(static_cast<double>(t.triangles.size()), lattice, 0.03 * lattice);
  // Every loop vertex is a vertex of the mesh, boundary points on the circle exactly on it.
  int on_circle = 0;
  for (const Eigen::Vector2d& p : t.points)
    if (std::abs((p - hole.center).norm() - 1.0) < 1e-6) {
      ++on_circle;
      EXPECT_NEAR((p - hole.center).norm(), 1.0, 1e-12);
    }
  EXPECT_GE(on_circle, static_cast<int>(hole.polygon.size()));
  for (const Eigen::Vector2d& corner : square.polygon)
    EXPECT_TRUE(std::any_of(t.points.begin(), t.points.end(), [&](const Eigen::Vector2d& p) { return p == corner; }));
}

}  // namespace
}  // namespace pqlayout
