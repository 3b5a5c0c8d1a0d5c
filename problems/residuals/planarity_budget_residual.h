// Planarity within a budget (per face f and each of its vertices v, stiffen): the vertex
// lies within ε ℓ_f of the face's auxiliary plane {x : n_f · (x − c_f) = d_f}, and pays only
// beyond,
//   r_fv = √w · max(0, |n_f · (p_v − c_f) − d_f| / ℓ_f − ε)
// ℓ_f = the face's mean diagonal, c_f a fixed point near the face (PlanarityResidual says
// why). A quad whose four vertices are ±e off its plane has its diagonals 2e apart, δ = 2e/ℓ,
// so ε = δ_allowed / 2. Unlike PlanarityResidual (δ → 0), this
// lets a shape optimisation spend the planarity tolerance the user granted
// (planarize.target_delta) instead of holding every face at the planarised δ.
// Parameters: plane = (n_f, d_f) (4, n_f on Ceres' SphereManifold<3>), p_v (3).
#pragma once

#include <ceres/ceres.h>
#include <Eigen/Core>

#include <cmath>

namespace pqlayout {

struct PlanarityBudgetResidual {
  PlanarityBudgetResidual(double weight, double mean_diagonal, double budget, const Eigen::Vector3d& centre)
      : scale(std::sqrt(weight)), inverse_length(1.0 / mean_diagonal), epsilon(budget), c(centre) {}

  template <typename T>
  bool operator()(const T* const plane, const T* const p, T* residual) const {
    using std::abs;
    const T distance =
        abs(plane[0] * (p[0] - c[0]) + plane[1] * (p[1] - c[1]) + plane[2] * (p[2] - c[2]) - plane[3]) * T(inverse_length);
    residual[0] = distance > T(epsilon) ? T(scale) * (distance - T(epsilon)) : T(0.0);
    return true;
  }

  static ceres::CostFunction* Create(double weight, double mean_diagonal, double budget, const Eigen::Vector3d& centre) {
    return new ceres::AutoDiffCostFunction<PlanarityBudgetResidual, 1, 4, 3>(
        new PlanarityBudgetResidual(weight, mean_diagonal, budget, centre));
  }

  const double scale, inverse_length, epsilon;
  const Eigen::Vector3d c;
};

}  // namespace pqlayout
