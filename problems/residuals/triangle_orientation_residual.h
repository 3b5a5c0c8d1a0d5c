// Triangle orientation (per triangular panel (p0, p1, p2)): planarisation must not turn a
// triangle inside out. A triangle needs no planarity, but its vertices are shared with
// quads whose planarity can push one of them across the opposite edge (a panel folded over
// its neighbour), and a panel that planarisation folded is cut into triangles that then need
// holding open (stage_planarize.cc). A hinge keeps the signed area, measured round the
// triangle's normal n₀ where the layout put it, at least κ of that area A₀:
//   r = √w · max(0, κ − n₀ · ((p1 − p0) × (p2 − p0)) / (2 A₀))
// with κ the stage's choice; zero while the triangle is open enough.
// Parameters: p0 (3), p1 (3), p2 (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include <Eigen/Core>

namespace pqlayout {

struct TriangleOrientationResidual {
  TriangleOrientationResidual(const Eigen::Vector3d& normal, double area, double fraction, double weight)
      : n(normal), scale(std::sqrt(weight) / (2.0 * area)), kappa(std::sqrt(weight) * fraction) {}

  template <typename T>
  bool operator()(const T* const p0, const T* const p1, const T* const p2, T* residual) const {
    const T u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    const T v[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    const T signed_area2 = T(n.x()) * (u[1] * v[2] - u[2] * v[1]) + T(n.y()) * (u[2] * v[0] - u[0] * v[2]) +
                           T(n.z()) * (u[0] * v[1] - u[1] * v[0]);
    const T r = T(kappa) - T(scale) * signed_area2;
    residual[0] = r > T(0.0) ? r : T(0.0);
    return true;
  }

  // normal: unit n₀; area: A₀ > 0; fraction: κ.
  static ceres::CostFunction* Create(const Eigen::Vector3d& normal, double area, double fraction, double weight) {
    return new ceres::AutoDiffCostFunction<TriangleOrientationResidual, 1, 3, 3, 3>(
        new TriangleOrientationResidual(normal, area, fraction, weight));
  }

  const Eigen::Vector3d n;
  const double scale;
  const double kappa;
};

}  // namespace pqlayout
