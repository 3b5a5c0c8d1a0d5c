// Seam smoothness (per seam edge e between face f on the seam's minus side and face g on its
// plus side, geometry/seams.h): the smoothness term across a seam, where g's values live in
// the other chart, u₊ = s·u₋ + a, so g's gradient is s times the gradient seen from f:
//   r_e = √A_e · h² · (∇u_f − s·∇u_g) / ℓ_e      (3 components)
// A_e, ℓ_e as in smoothness_residual.h. Parameters: u at the edge's vertices i, j and f's
// third vertex k as f sees them (minus copies), then u at i, j and g's third vertex l as g
// sees them (plus copies); G_f, G_g hold the basis gradients in the order (i, j, k), (i, j, l).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "problems/residuals/p1_gradient.h"

namespace pqlayout {

struct SeamSmoothnessResidual {
  SeamSmoothnessResidual(const Eigen::Matrix3d& basis_gradients_f, const Eigen::Matrix3d& basis_gradients_g,
                         double sign, double edge_area, double centroid_distance, double spacing)
      : Gf(basis_gradients_f), Gg(basis_gradients_g), s(sign),
        scale(std::sqrt(edge_area) * spacing * spacing / centroid_distance) {}

  template <typename T>
  bool operator()(const T* const u_i, const T* const u_j, const T* const u_k, const T* const v_i,
                  const T* const v_j, const T* const v_l, T* residual) const {
    const Eigen::Matrix<T, 3, 1> jump = P1Gradient(Gf, u_i, u_j, u_k) - T(s) * P1Gradient(Gg, v_i, v_j, v_l);
    for (int c = 0; c < 3; ++c) residual[c] = T(scale) * jump[c];
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Matrix3d& basis_gradients_f,
                                     const Eigen::Matrix3d& basis_gradients_g, double sign, double edge_area,
                                     double centroid_distance, double spacing) {
    return new ceres::AutoDiffCostFunction<SeamSmoothnessResidual, 3, 1, 1, 1, 1, 1, 1>(new SeamSmoothnessResidual(
        basis_gradients_f, basis_gradients_g, sign, edge_area, centroid_distance, spacing));
  }

  const Eigen::Matrix3d Gf, Gg;
  const double s, scale;
};

}  // namespace pqlayout
