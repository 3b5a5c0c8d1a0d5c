// Signed planarity of a sub-quad (a, b, c, d) of a face, in cyclic order (stiffen's
// constraint function; its Jacobian spans the directions that bend the panel):
//   δ_s = ((p_b − p_a) · n) / |n| / (½ (|p_c − p_a| + |p_d − p_b|)),  n = (p_c − p_a) × (p_d − p_b)
// |δ_s| is the SPEC planarity δ (distance between the diagonals over their mean length); the
// sign says on which side of a's diagonal b's diagonal passes, so that δ_s is smooth where
// the panel is planar (δ = |δ_s| is not). Parallel diagonals (a fold, not a panel): 0.
// Parameters: p_a, p_b, p_c, p_d (3 each).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct SignedPlanarityResidual {
  template <typename T>
  bool operator()(const T* const a, const T* const b, const T* const c, const T* const d, T* residual) const {
    using std::sqrt;
    T d1[3], d2[3], ab[3];
    for (int k = 0; k < 3; ++k) d1[k] = c[k] - a[k], d2[k] = d[k] - b[k], ab[k] = b[k] - a[k];
    const T n[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0]};
    const T n_norm = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const T mean_diagonal = T(0.5) * (sqrt(d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]) +
                                      sqrt(d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2]));
    if (!(n_norm > T(1e-12) * mean_diagonal * mean_diagonal)) {
      residual[0] = T(0.0);
      return true;
    }
    residual[0] = (ab[0] * n[0] + ab[1] * n[1] + ab[2] * n[2]) / n_norm / mean_diagonal;
    return true;
  }

  static ceres::CostFunction* Create() {
    return new ceres::AutoDiffCostFunction<SignedPlanarityResidual, 1, 3, 3, 3, 3>(new SignedPlanarityResidual);
  }
};

}  // namespace pqlayout
