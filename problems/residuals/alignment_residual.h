// Alignment (per face f): the level lines of φ follow the guidance direction d_f, i.e. ∇φ is
// orthogonal to d_f:
//   r_f = √(w_f A_f) · h · ⟨∇φ_f, d_f⟩
// w_f = guidance weight, A_f = face area, h = layout spacing. With h|∇φ| ≈ 1 (spacing term),
// r_f ≈ √(w_f A_f) · sin(angle between level line and d_f): dimension √area, so the sum of
// squares is an area integral and does not depend on the mesh resolution.
// Parameters: φ at the face's three vertices (one scalar block each).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "problems/residuals/p1_gradient.h"

namespace pqlayout {

struct AlignmentResidual {
  AlignmentResidual(const Eigen::Matrix3d& basis_gradients, const Eigen::Vector3d& direction, double weight,
                    double area, double spacing)
      : G(basis_gradients), d(direction), scale(std::sqrt(weight * area) * spacing) {}

  template <typename T>
  bool operator()(const T* const phi_a, const T* const phi_b, const T* const phi_c, T* residual) const {
    residual[0] = T(scale) * P1Gradient(G, phi_a, phi_b, phi_c).dot(d.cast<T>());
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Matrix3d& basis_gradients, const Eigen::Vector3d& direction,
                                     double weight, double area, double spacing) {
    return new ceres::AutoDiffCostFunction<AlignmentResidual, 1, 1, 1, 1>(
        new AlignmentResidual(basis_gradients, direction, weight, area, spacing));
  }

  const Eigen::Matrix3d G;
  const Eigen::Vector3d d;
  const double scale;
};

}  // namespace pqlayout
