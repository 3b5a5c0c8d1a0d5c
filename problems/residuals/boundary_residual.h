// Boundary (per vertex v on the reference boundary, corners excepted — they are fixed): the
// vertex stays on the reference boundary polylines. The vector from the closest boundary
// point c(p) (found afresh at every evaluation) to p_v:
//   r_v = √w · (p_v − c(p_v)) / h                               (3 components)
//   ∂r/∂p = √w (I − t tᵀ) / h   where c lies inside a boundary edge of tangent t,
//           √w I / h            where c is a polyline vertex.
// So the vertex may slide along the boundary, across any number of boundary edges.
// Like ClosenessResidual, it remembers its last answer (RememberedClosestPoint).
// Parameters: p_v (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "geometry/closest_point.h"

namespace pqlayout {

class BoundaryResidual final : public ceres::SizedCostFunction<3, 3> {
 public:
  // query must outlive the residual.
  BoundaryResidual(const ClosestPointQuery* query, double weight, double spacing)
      : query_(query), scale_(std::sqrt(weight) / spacing) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Vector3d p(parameters[0][0], parameters[0][1], parameters[0][2]);
    const SurfacePoint& c = last_.OnBoundary(*query_, p);
    for (int k = 0; k < 3; ++k) residuals[k] = scale_ * (p[k] - c.point[k]);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> jacobian(jacobians[0]);
      jacobian = scale_ * Eigen::Matrix3d::Identity();
      if (c.inside_edge) jacobian -= scale_ * c.tangent * c.tangent.transpose();
    }
    return true;
  }

 private:
  const ClosestPointQuery* query_;
  const double scale_;
  RememberedClosestPoint last_;
};

}  // namespace pqlayout
