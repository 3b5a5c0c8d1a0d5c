// Closeness (per vertex v): the vertex stays on the reference surface. The signed distance
// from p_v to the reference triangle mesh, its closest point c(p) found afresh (CGAL AABB
// tree) at every evaluation, not once per solve:
//   r_v = √w · s · |p_v − c(p_v)| / h,   s = sign((p_v − c) · n_c)
//   ∂r/∂p = √w · s (p_v − c) / |p_v − c| / h   (the gradient of the distance; n_c on the surface)
// with n_c the normal of the closest triangle. Exact, so a vertex may slide across any
// number of reference triangles within one solve and the solver still sees the surface, not
// a tangent plane that is only right near where the solve started. Only the distance is
// penalised: sliding along the surface is free here (the anchor term keeps it small).
// The residual remembers its last answer (RememberedClosestPoint): the same position again
// (the Jacobian at a step just taken) is answered from memory, a new one searched with the
// last triangle as hint (exact either way; the search is just shorter).
// Parameters: p_v (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "geometry/closest_point.h"

namespace pqlayout {

class ClosenessResidual final : public ceres::SizedCostFunction<1, 3> {
 public:
  // query must outlive the residual.
  ClosenessResidual(const ClosestPointQuery* query, double weight, double spacing)
      : query_(query), scale_(std::sqrt(weight) / spacing) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Vector3d p(parameters[0][0], parameters[0][1], parameters[0][2]);
    const SurfacePoint& c = last_.OnSurface(*query_, p);
    const Eigen::Vector3d offset = p - c.point;
    const double sign = offset.dot(c.normal) < 0.0 ? -1.0 : 1.0;
    const double distance = offset.norm();
    residuals[0] = scale_ * sign * distance;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      const Eigen::Vector3d gradient = distance > 1e-12 ? Eigen::Vector3d(sign * offset / distance) : c.normal;
      for (int k = 0; k < 3; ++k) jacobians[0][k] = scale_ * gradient[k];
    }
    return true;
  }

 private:
  const ClosestPointQuery* query_;
  const double scale_;
  RememberedClosestPoint last_;
};

}  // namespace pqlayout
