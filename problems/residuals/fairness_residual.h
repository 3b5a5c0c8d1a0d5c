// Fairness (per valence-4 interior vertex v and each of its two mesh polylines a–v–b):
// the polyline does not kink at v,
//   r = √w · (p_a − 2 p_v + p_b) / h                           (3 components)
// Parameters: p_a (3), p_v (3), p_b (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct FairnessResidual {
  FairnessResidual(double weight, double spacing) : scale(std::sqrt(weight) / spacing) {}

  template <typename T>
  bool operator()(const T* const a, const T* const v, const T* const b, T* residual) const {
    for (int k = 0; k < 3; ++k) residual[k] = T(scale) * (a[k] - T(2.0) * v[k] + b[k]);
    return true;
  }

  static ceres::CostFunction* Create(double weight, double spacing) {
    return new ceres::AutoDiffCostFunction<FairnessResidual, 3, 3, 3, 3>(new FairnessResidual(weight, spacing));
  }

  const double scale;
};

}  // namespace pqlayout
