// Boundary (per vertex v on the reference boundary): the vertex stays on the boundary
// polyline, measured to the line through its closest boundary point c_v with tangent t
// (refreshed between solves):
//   r_v = √w · ((p_v − c_v) − ((p_v − c_v) · t) t) / h        (3 components)
// Parameters: p_v (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct BoundaryResidual {
  BoundaryResidual(const Eigen::Vector3d& closest, const Eigen::Vector3d& tangent, double weight, double spacing)
      : c(closest), t(tangent.normalized()), scale(std::sqrt(weight) / spacing) {}

  template <typename T>
  bool operator()(const T* const p, T* residual) const {
    const T dx = p[0] - T(c.x()), dy = p[1] - T(c.y()), dz = p[2] - T(c.z());
    const T along = dx * T(t.x()) + dy * T(t.y()) + dz * T(t.z());
    residual[0] = T(scale) * (dx - along * T(t.x()));
    residual[1] = T(scale) * (dy - along * T(t.y()));
    residual[2] = T(scale) * (dz - along * T(t.z()));
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& closest, const Eigen::Vector3d& tangent, double weight,
                                     double spacing) {
    return new ceres::AutoDiffCostFunction<BoundaryResidual, 3, 3>(new BoundaryResidual(closest, tangent, weight, spacing));
  }

  const Eigen::Vector3d c, t;
  const double scale;
};

}  // namespace pqlayout
