// Closest points on the reference surface (CGAL's AABB tree over its triangles) and on its
// boundary polylines (a second AABB tree over the boundary edges). Both are exact; an
// optional hint (a triangle, resp. boundary edge, index — e.g. the previous answer for a point
// that moved a little) only makes the search faster: the tree traversal starts from the
// hint's distance instead of a k-d-tree guess and prunes every box farther away.
#pragma once

#include <array>
#include <memory>
#include <utility>
#include <vector>

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
  // What the trees are built from, copied out of a surface (Gather), so that the building can
  // run on another thread while the surface is in use (SurfaceModel::IndexClosestPointsInBackground).
  struct Geometry {
    std::vector<std::array<Eigen::Vector3d, 3>> triangles;
    std::vector<Eigen::Vector3d> normals;                                 // per triangle
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boundary;   // boundary edges
  };
  static Geometry Gather(const SurfaceModel& surface);

  explicit ClosestPointQuery(const SurfaceModel& surface);
  explicit ClosestPointQuery(const Geometry& geometry);
  ~ClosestPointQuery();
  SurfacePoint OnSurface(const Eigen::Vector3d& p, int hint = -1) const;
  SurfacePoint OnBoundary(const Eigen::Vector3d& p, int hint = -1) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

// One point's closest point, remembered: for a residual or manifold that asks for the closest
// point of one moving vertex at every evaluation. Asked again for the same position (to the
// bit), it answers from memory — Levenberg–Marquardt evaluates the residuals at a candidate
// step and, once the step is taken, the Jacobian at the same point, so every second query was
// a repeat (the planarisation of the 5,328-quad lifted grid spent ~7 % of its time on them).
// Asked for a new position, it hands the last answer's element to the query as the hint.
// The same answer either way: with the last answer as hint the tree search returns that answer
// again (nothing is strictly closer). Like the hint it replaces, one object serves one Ceres
// residual block, which Ceres evaluates from one thread at a time, each evaluation joined
// before the next starts.
class RememberedClosestPoint {
 public:
  const SurfacePoint& OnSurface(const ClosestPointQuery& query, const Eigen::Vector3d& p) const {
    return Ask(p, [&](int hint) { return query.OnSurface(p, hint); });
  }
  const SurfacePoint& OnBoundary(const ClosestPointQuery& query, const Eigen::Vector3d& p) const {
    return Ask(p, [&](int hint) { return query.OnBoundary(p, hint); });
  }

 private:
  template <typename Query>
  const SurfacePoint& Ask(const Eigen::Vector3d& p, const Query& query) const {
    if (!known_ || p != position_) {
      answer_ = query(known_ ? answer_.element : -1);
      position_ = p;
      known_ = true;
    }
    return answer_;
  }
  mutable bool known_ = false;
  mutable Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  mutable SurfacePoint answer_;
};

}  // namespace pqlayout
