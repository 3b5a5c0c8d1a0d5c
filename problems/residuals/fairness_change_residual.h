// Fairness change (per valence-4 interior vertex v and each of its two mesh polylines
// a–v–b, stiffen): the polyline's second difference stays what it was in a reference
// configuration p⁰ (the planarised mesh), so that a smooth change of shape adds no kinks,
//   r = √w · ((p_a − 2 p_v + p_b) − (p⁰_a − 2 p⁰_v + p⁰_b)) / h      (3 components)
// Unlike FairnessResidual (straight polylines), a curved roof pays nothing for its curvature,
// only for what the change does to it.
// Parameters: p_a (3), p_v (3), p_b (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include <Eigen/Core>

namespace pqlayout {

struct FairnessChangeResidual {
  FairnessChangeResidual(const Eigen::Vector3d& reference_difference, double weight, double spacing)
      : d0(reference_difference), scale(std::sqrt(weight) / spacing) {}

  template <typename T>
  bool operator()(const T* const a, const T* const v, const T* const b, T* residual) const {
    for (int k = 0; k < 3; ++k) residual[k] = T(scale) * (a[k] - T(2.0) * v[k] + b[k] - T(d0[k]));
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& reference_difference, double weight, double spacing) {
    return new ceres::AutoDiffCostFunction<FairnessChangeResidual, 3, 3, 3, 3>(
        new FairnessChangeResidual(reference_difference, weight, spacing));
  }

  const Eigen::Vector3d d0;
  const double scale;
};

}  // namespace pqlayout
