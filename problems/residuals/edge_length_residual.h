// Edge length (per mesh edge (i, j)): planarisation must not make a face planar by letting
// two of its vertices run into each other (a quad with a vanishing edge is a planar
// triangle, and an edge shorter than the members are deep is a joint, not a member). A
// hinge keeps every edge at least ℓ_min long:
//   r_ij = √w · max(0, ℓ_min − |p_i − p_j|) / h
// with ℓ_min = ¼ min(ℓ⁰_ij, h) (the stage's choice), ℓ⁰ the edge's length in the extracted
// mesh; zero while the edge is longer.
// Parameters: p_i (3), p_j (3).
#pragma once

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

namespace pqlayout {

struct EdgeLengthResidual {
  EdgeLengthResidual(double min_length, double weight, double spacing)
      : l_min(min_length), scale(std::sqrt(weight) / spacing) {}

  template <typename T>
  bool operator()(const T* const p, const T* const q, T* residual) const {
    const T dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    const T squared = dx * dx + dy * dy + dz * dz;
    if (squared >= T(l_min * l_min)) {  // |p − q| ≥ ℓ_min: no square root where it is not needed
      residual[0] = T(0.0);
      return true;
    }
    const T length = squared > T(0.0) ? T(sqrt(squared)) : T(0.0);
    residual[0] = T(scale) * (T(l_min) - length);
    return true;
  }

  static ceres::CostFunction* Create(double min_length, double weight, double spacing) {
    return new ceres::AutoDiffCostFunction<EdgeLengthResidual, 1, 3, 3>(
        new EdgeLengthResidual(min_length, weight, spacing));
  }

  const double l_min;
  const double scale;
};

}  // namespace pqlayout
