// Transition (per vertex of a seam, geometry/seams.h): the level-set function u (φ or ψ) on
// the two sides of a seam differs by the seam's transition, u₊ = s·u₋ + a (s = ±1; a a whole
// number of levels, so that level lines meet level lines across the seam):
//   r_v = √(λ A_v) · (u₊ − s·u₋ − a)
// A_v = the vertex's lumped area (so Σ r² has the dimension of area like every other term),
// λ = stiffness, large: the transition is a constraint that the stage finally makes exact.
// At a seam's interior tip (a branch point) there is one copy u: r = √(λ A_v) · ((1 − s)·u − a).
// Parameters: u₋ and u₊ (one scalar block each), or u alone at a tip.
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct TransitionResidual {
  TransitionResidual(double sign, double offset, double vertex_area, double stiffness)
      : s(sign), a(offset), scale(std::sqrt(stiffness * vertex_area)) {}

  template <typename T>
  bool operator()(const T* const u_minus, const T* const u_plus, T* residual) const {
    residual[0] = T(scale) * (u_plus[0] - T(s) * u_minus[0] - T(a));
    return true;
  }
  template <typename T>
  bool operator()(const T* const u, T* residual) const {
    residual[0] = T(scale) * (T(1.0 - s) * u[0] - T(a));
    return true;
  }

  static ceres::CostFunction* Create(double sign, double offset, double vertex_area, double stiffness) {
    return new ceres::AutoDiffCostFunction<TransitionResidual, 1, 1, 1>(
        new TransitionResidual(sign, offset, vertex_area, stiffness));
  }
  static ceres::CostFunction* CreateTip(double sign, double offset, double vertex_area, double stiffness) {
    return new ceres::AutoDiffCostFunction<TransitionResidual, 1, 1>(
        new TransitionResidual(sign, offset, vertex_area, stiffness));
  }

  const double s, a, scale;
};

}  // namespace pqlayout
