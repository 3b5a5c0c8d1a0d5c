// Transversality (per face f): the two families cross at an angle of at least θ_min and
// with a consistent orientation, so quads neither degenerate nor fold over. With
//   s_f = n · (∇φ × ∇ψ) / max(|∇φ| |∇ψ|, 1/h²)
//   r_f = √A_f · max(0, sin θ_min − s_f)
// s_f is the signed sine of the crossing angle wherever the lines are at least as dense as
// h (s_f ≤ 0 is a fold-over of the map (φ, ψ)), and the signed area of the map relative to
// an h × h cell where they are sparser. The hinge is zero while the crossing is steep
// enough. Unlike the plain sine, s_f keeps a non-zero derivative where a family collapses
// (∇ψ → 0), so the optimiser cannot escape a fold-over by flattening ψ; unlike the plain
// area, dense lines cannot satisfy it at a shallow angle.
// Parameters: φ at the face's three vertices, then ψ at the same vertices.
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "problems/residuals/p1_gradient.h"

namespace pqlayout {

struct TransversalityResidual {
  TransversalityResidual(const Eigen::Matrix3d& basis_gradients, const Eigen::Vector3d& normal,
                         double min_angle_radians, double area, double spacing)
      : G(basis_gradients), n(normal), sin_min(std::sin(min_angle_radians)), sqrt_area(std::sqrt(area)),
        h_squared(spacing * spacing) {}

  template <typename T>
  bool operator()(const T* const phi_a, const T* const phi_b, const T* const phi_c, const T* const psi_a,
                  const T* const psi_b, const T* const psi_c, T* residual) const {
    const T sine = SignedCrossingSine(G, n, h_squared, phi_a, phi_b, phi_c, psi_a, psi_b, psi_c);
    residual[0] = sine < T(sin_min) ? T(sqrt_area) * (T(sin_min) - sine) : T(0.0);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Matrix3d& basis_gradients, const Eigen::Vector3d& normal,
                                     double min_angle_radians, double area, double spacing) {
    return new ceres::AutoDiffCostFunction<TransversalityResidual, 1, 1, 1, 1, 1, 1, 1>(
        new TransversalityResidual(basis_gradients, normal, min_angle_radians, area, spacing));
  }

  const Eigen::Matrix3d G;
  const Eigen::Vector3d n;
  const double sin_min;
  const double sqrt_area;
  const double h_squared;
};

}  // namespace pqlayout
