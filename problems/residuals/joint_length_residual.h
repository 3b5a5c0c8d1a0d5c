// Joint length (per mesh edge (i, j) shorter than the section depth, stiffen): the edge is a
// joint of the frame (its ends are one node, problems/grid_frame.h) and must stay one, so a
// hinge keeps it below ℓ_max = max(0.9 × section depth, its planarised length):
//   r_ij = √w · max(0, |p_i − p_j| − ℓ_max) / h
// zero while the edge is shorter.
// Parameters: p_i (3), p_j (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct JointLengthResidual {
  JointLengthResidual(double max_length, double weight, double spacing)
      : l_max(max_length), scale(std::sqrt(weight) / spacing) {}

  template <typename T>
  bool operator()(const T* const p, const T* const q, T* residual) const {
    using std::sqrt;
    const T dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    const T squared = dx * dx + dy * dy + dz * dz;
    residual[0] = squared > T(l_max * l_max) ? T(scale) * (sqrt(squared) - T(l_max)) : T(0.0);
    return true;
  }

  static ceres::CostFunction* Create(double max_length, double weight, double spacing) {
    return new ceres::AutoDiffCostFunction<JointLengthResidual, 1, 3, 3>(new JointLengthResidual(max_length, weight, spacing));
  }

  const double l_max;
  const double scale;
};

}  // namespace pqlayout
