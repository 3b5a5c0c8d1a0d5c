// Anchor (per vertex v): the vertex stays near where the layout put it, p⁰_v (the extracted
// mesh), so that planarisation moves the grid no more than it must:
//   r_v = √w · (p_v − p⁰_v) / h                                 (3 components)
// Parameters: p_v (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct AnchorResidual {
  AnchorResidual(const Eigen::Vector3d& anchor, double weight, double spacing)
      : a(anchor), scale(std::sqrt(weight) / spacing) {}

  template <typename T>
  bool operator()(const T* const p, T* residual) const {
    for (int k = 0; k < 3; ++k) residual[k] = T(scale) * (p[k] - T(a[k]));
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& anchor, double weight, double spacing) {
    return new ceres::AutoDiffCostFunction<AnchorResidual, 3, 3>(new AnchorResidual(anchor, weight, spacing));
  }

  const Eigen::Vector3d a;
  const double scale;
};

}  // namespace pqlayout
