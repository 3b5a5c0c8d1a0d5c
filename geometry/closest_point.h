// Closest points on the reference surface (CGAL's AABB tree over its triangles) and on its
// boundary polylines (brute force over the boundary edges, which are few).
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

class ClosestPointQuery {
 public:
  explicit ClosestPointQuery(const SurfaceModel& surface);
  ~ClosestPointQuery();
  SurfacePoint OnSurface(const Eigen::Vector3d& p) const;
  SurfacePoint OnBoundary(const Eigen::Vector3d& p) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boundary_edges_;
};

}  // namespace pqlayout
