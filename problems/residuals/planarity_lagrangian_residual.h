// Planarity as an inequality in an augmented Lagrangian (per sub-quad (a, b, c, d) of a face,
// in cyclic order; stiffen): the constraint g = δ(a, b, c, d) − δ_allowed ≤ 0 with
//   δ = |(p_b − p_a) · n| / |n| / (½ (|p_c − p_a| + |p_d − p_b|)),  n = (p_c − p_a) × (p_d − p_b)
// (the SPEC planarity δ: distance between the diagonals over their mean length), enters
// the objective as the Powell–Hestenes–Rockafellar term (1/2ρ)(max(0, λ + ρ g)² − λ²), written
// as one square up to the constant:
//   r = max(0, λ/√ρ + √ρ · g)
// λ (multiplier, ≥ 0) and ρ (penalty) are read through pointers, so that the outer loop can
// update them between solves without rebuilding the problem.
// Parameters: p_a, p_b, p_c, p_d (3 each).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct PlanarityLagrangianResidual {
  PlanarityLagrangianResidual(const double* multiplier, const double* penalty, double allowed)
      : lambda(multiplier), rho(penalty), delta_allowed(allowed) {}

  template <typename T>
  bool operator()(const T* const a, const T* const b, const T* const c, const T* const d, T* residual) const {
    using std::abs;
    using std::sqrt;
    T d1[3], d2[3], ab[3];
    for (int k = 0; k < 3; ++k) d1[k] = c[k] - a[k], d2[k] = d[k] - b[k], ab[k] = b[k] - a[k];
    const T n[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0]};
    const T n_norm = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const T mean_diagonal = T(0.5) * (sqrt(d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]) +
                                      sqrt(d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2]));
    if (!(n_norm > T(1e-12) * mean_diagonal * mean_diagonal)) {  // parallel diagonals: a fold, not a panel
      residual[0] = T(0.0);
      return true;
    }
    const T delta = abs(ab[0] * n[0] + ab[1] * n[1] + ab[2] * n[2]) / n_norm / mean_diagonal;
    const double root = std::sqrt(*rho);
    const T r = T(*lambda / root) + T(root) * (delta - T(delta_allowed));
    residual[0] = r > T(0.0) ? r : T(0.0);
    return true;
  }

  static ceres::CostFunction* Create(const double* multiplier, const double* penalty, double allowed) {
    return new ceres::AutoDiffCostFunction<PlanarityLagrangianResidual, 1, 3, 3, 3, 3>(
        new PlanarityLagrangianResidual(multiplier, penalty, allowed));
  }

  const double* lambda;
  const double* rho;
  const double delta_allowed;
};

}  // namespace pqlayout
