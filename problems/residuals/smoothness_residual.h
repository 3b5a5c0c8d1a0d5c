// Smoothness (per interior edge e between faces f and g): the gradient of u (φ or ψ) does
// not jump across the edge, so level lines do not kink:
//   r_e = √A_e · h² · (∇u_f − ∇u_g) / ℓ_e      (3 components)
// A_e = (A_f + A_g) / 3, the area the edge stands for; ℓ_e = distance between the faces'
// centroids. (∇u_f − ∇u_g) / ℓ_e approximates the Hessian of u, so Σ r_e² ≈ ∫ h⁴ |Hess u|²:
// dimensionless and independent of the mesh resolution. Parameters: u at the edge's two
// vertices i, j, at f's third vertex k and at g's third vertex l; G_f, G_g hold the basis
// gradients in the order (i, j, k) and (i, j, l).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "problems/residuals/p1_gradient.h"

namespace pqlayout {

struct SmoothnessResidual {
  SmoothnessResidual(const Eigen::Matrix3d& basis_gradients_f, const Eigen::Matrix3d& basis_gradients_g,
                     double edge_area, double centroid_distance, double spacing)
      : Gf(basis_gradients_f), Gg(basis_gradients_g),
        scale(std::sqrt(edge_area) * spacing * spacing / centroid_distance) {}

  template <typename T>
  bool operator()(const T* const u_i, const T* const u_j, const T* const u_k, const T* const u_l,
                  T* residual) const {
    const Eigen::Matrix<T, 3, 1> jump = P1Gradient(Gf, u_i, u_j, u_k) - P1Gradient(Gg, u_i, u_j, u_l);
    for (int c = 0; c < 3; ++c) residual[c] = T(scale) * jump[c];
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Matrix3d& basis_gradients_f,
                                     const Eigen::Matrix3d& basis_gradients_g, double edge_area,
                                     double centroid_distance, double spacing) {
    return new ceres::AutoDiffCostFunction<SmoothnessResidual, 3, 1, 1, 1, 1>(
        new SmoothnessResidual(basis_gradients_f, basis_gradients_g, edge_area, centroid_distance, spacing));
  }

  const Eigen::Matrix3d Gf, Gg;
  const double scale;
};

}  // namespace pqlayout
