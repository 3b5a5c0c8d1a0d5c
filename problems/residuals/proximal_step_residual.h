// Proximal step (per free vertex v, stiffen): the linearised objective g·(p − p_k) plus the
// step's own cost |p − p_k|²/(2μ), written as one square,
//   ½ r_v² = ½ |p_v − p_k,v + μ g_v|² / μ = g_v·(p_v − p_k,v) + |p_v − p_k,v|²/(2μ) + const,
//   r_v = (p_v − c_v) / √μ,  c_v = p_k,v − μ g_v                 (3 components)
// so that a Ceres least-squares solve with the constraint terms (planarity, …) added is a
// projected gradient step of length μ on the objective (here C/C₀, g its gradient).
// Parameters: p_v (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include <Eigen/Core>

namespace pqlayout {

struct ProximalStepResidual {
  ProximalStepResidual(const Eigen::Vector3d& target, double step) : c(target), scale(1.0 / std::sqrt(step)) {}

  template <typename T>
  bool operator()(const T* const p, T* residual) const {
    for (int k = 0; k < 3; ++k) residual[k] = T(scale) * (p[k] - T(c[k]));
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& target, double step) {
    return new ceres::AutoDiffCostFunction<ProximalStepResidual, 3, 3>(new ProximalStepResidual(target, step));
  }

  const Eigen::Vector3d c;
  const double scale;
};

}  // namespace pqlayout
