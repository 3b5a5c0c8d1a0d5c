// Crossing barrier (per face f): the crossing rounds' guarantee. With the transversality
// term's signed sine
//   s_f = n · (∇φ × ∇ψ) / max(|∇φ| |∇ψ|, 1/h²)
// (transversality_residual.h) and a floor t < sin θ_min below which no face may go,
//   r_f = √A_f · (sin θ_min − s_f) / (s_f − t)   for t < s_f < sin θ_min,
//   r_f = 0                                     for s_f ≥ sin θ_min,
// and the evaluation fails for s_f ≤ t, so Ceres rejects any step that would take a face to
// the floor (the trust region shrinks instead). r_f² grows without bound as s_f → t and is
// zero, with a zero derivative, at s_f = sin θ_min. Starting from a state with every face
// above t, every accepted iterate keeps every face above t: the worst crossing cannot be
// traded away to its neighbours, as the hinge alone allows.
// Parameters: φ at the face's three vertices, then ψ at the same vertices.
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "problems/residuals/p1_gradient.h"

namespace pqlayout {

struct CrossingBarrierResidual {
  CrossingBarrierResidual(const Eigen::Matrix3d& basis_gradients, const Eigen::Vector3d& normal,
                          double min_angle_radians, double floor, double area, double spacing)
      : G(basis_gradients), n(normal), sin_min(std::sin(min_angle_radians)), floor(floor),
        sqrt_area(std::sqrt(area)), h_squared(spacing * spacing) {}

  template <typename T>
  bool operator()(const T* const phi_a, const T* const phi_b, const T* const phi_c, const T* const psi_a,
                  const T* const psi_b, const T* const psi_c, T* residual) const {
    const T sine = SignedCrossingSine(G, n, h_squared, phi_a, phi_b, phi_c, psi_a, psi_b, psi_c);
    if (!(sine > T(floor))) return false;
    residual[0] = sine < T(sin_min) ? T(sqrt_area) * (T(sin_min) - sine) / (sine - T(floor)) : T(0.0);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Matrix3d& basis_gradients, const Eigen::Vector3d& normal,
                                     double min_angle_radians, double floor, double area, double spacing) {
    return new ceres::AutoDiffCostFunction<CrossingBarrierResidual, 1, 1, 1, 1, 1, 1, 1>(
        new CrossingBarrierResidual(basis_gradients, normal, min_angle_radians, floor, area, spacing));
  }

  const Eigen::Matrix3d G;
  const Eigen::Vector3d n;
  const double sin_min;
  const double floor;
  const double sqrt_area;
  const double h_squared;
};

}  // namespace pqlayout
