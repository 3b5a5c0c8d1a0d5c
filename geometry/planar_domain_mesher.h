// MeshPlanarDomain: quality triangulation of a planar polygonal domain with holes, by CGAL's
// 2D constrained Delaunay refinement (Ruppert/Shewchuk, Delaunay_mesher_2); above 200k
// expected triangles the interior is first seeded with a triangular lattice of 0.68 ×
// edge_length, so that the refinement only meshes the band along the boundary (968k-triangle
// Great Court plan: 10.6 s → 1.6 s). Every loop vertex
// is kept, boundary points on axis-parallel segments are snapped exactly onto the segment's
// line, and boundary points of circular loops exactly onto the circle. The built-in surfaces
// (surface_generators.h) lift this mesh to z = f(x, y).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "base/status.h"

namespace pqlayout {

// One closed boundary loop of a planar domain. If is_circle, vertices that end up on this
// loop after meshing are projected exactly onto the circle (center, radius).
struct DomainLoop {
  std::vector<Eigen::Vector2d> polygon;  // closed implicitly, no repeated first point
  bool is_circle = false;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
};

struct PlanarTriangulation {
  std::vector<Eigen::Vector2d> points;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise
};

// loops[0] is the outer boundary, the rest are holes. Every polygon vertex of every loop is
// a vertex of the result (so corners are exact). Triangles have edges of about
// edge_length (no longer than edge_length) and minimum angle >= 20 degrees.
Status MeshPlanarDomain(const std::vector<DomainLoop>& loops, double edge_length,
                        PlanarTriangulation* out);

// Helper: a circle as a polygon with segments no longer than edge_length.
DomainLoop CircleLoop(const Eigen::Vector2d& center, double radius, double edge_length);

}  // namespace pqlayout
