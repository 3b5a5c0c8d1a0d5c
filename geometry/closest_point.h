// Closest points on the reference surface (CGAL's AABB tree over its triangles) and on its
// boundary polylines (a second AABB tree over the boundary edges). Both are exact; an
// optional hint (a triangle, resp. boundary edge, index — e.g. the previous answer for a point
// that moved a little) only makes the search faster: the tree traversal starts from the
// hint's distance instead of a k-d-tree guess and prunes every box farther away.
#pragma once

#include <memory>

#include <Eigen/Core>

#include "geometry/surface_model.h"

namespace pqlayout {

struct SurfacePoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // of the triangle (surface) or unused
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX(); // of the boundary edge (boundary) or unused
  int element = -1;                                   // triangle or boundary-edge index
  bool inside_edge = false;                           // boundary: the point is inside the edge, not an end
  double distance = 0.0;
};

// Barycentric coordinates of p's projection onto the plane of triangle `face` of s, in the
// order of face_vertices; not clamped, so that outside the triangle a P1 function extends
// linearly. (1, 0, 0) for a degenerate triangle.
Eigen::Vector3d TriangleBarycentric(const SurfaceModel& s, int face, const Eigen::Vector3d& p);

class ClosestPointQuery {
 public:
  explicit ClosestPointQuery(const SurfaceModel& surface);
  ~ClosestPointQuery();
  SurfacePoint OnSurface(const Eigen::Vector3d& p, int hint = -1) const;
  SurfacePoint OnBoundary(const Eigen::Vector3d& p, int hint = -1) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace pqlayout
