// Spacing (per face f): neighbouring level lines of u (φ or ψ) lie h apart, h|∇u| = 1:
//   r_f = √A_f · (h |∇u_f| − 1)
// Parameters: u at the face's three vertices.
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "problems/residuals/p1_gradient.h"

namespace pqlayout {

struct SpacingResidual {
  SpacingResidual(const Eigen::Matrix3d& basis_gradients, double area, double spacing)
      : G(basis_gradients), sqrt_area(std::sqrt(area)), h(spacing) {}

  template <typename T>
  bool operator()(const T* const u_a, const T* const u_b, const T* const u_c, T* residual) const {
    residual[0] = T(sqrt_area) * (T(h) * SafeNorm(P1Gradient(G, u_a, u_b, u_c)) - T(1.0));
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Matrix3d& basis_gradients, double area, double spacing) {
    return new ceres::AutoDiffCostFunction<SpacingResidual, 1, 1, 1, 1>(
        new SpacingResidual(basis_gradients, area, spacing));
  }

  const Eigen::Matrix3d G;
  const double sqrt_area;
  const double h;
};

}  // namespace pqlayout
