// Closeness (per vertex v): the vertex stays on the reference surface. With c_v its closest
// point on the reference (refreshed between solves) and n_c the surface normal there,
//   r_v = √w · [ (p_v − c_v) · n_c,  √τ (p_v − c_v) · t1,  √τ (p_v − c_v) · t2 ] / h
// (t1, t2 span the tangent plane). The normal component holds the vertex on the surface;
// the weak tangential one (τ = 0.1) keeps each round's step proximal, so planarity can
// slide vertices along the surface but not drag them away. Parameters: p_v (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct ClosenessResidual {
  static constexpr double kTangentialWeight = 0.1;  // τ

  ClosenessResidual(const Eigen::Vector3d& closest, const Eigen::Vector3d& normal, double weight, double spacing)
      : c(closest), scale(std::sqrt(weight) / spacing) {
    const Eigen::Vector3d n = normal.normalized();
    const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d t1 = n.cross(axis).normalized(), t2 = n.cross(t1);
    frame.row(0) = n;
    frame.row(1) = std::sqrt(kTangentialWeight) * t1;
    frame.row(2) = std::sqrt(kTangentialWeight) * t2;
  }

  template <typename T>
  bool operator()(const T* const p, T* residual) const {
    const T d[3] = {p[0] - T(c.x()), p[1] - T(c.y()), p[2] - T(c.z())};
    for (int r = 0; r < 3; ++r)
      residual[r] = T(scale) * (T(frame(r, 0)) * d[0] + T(frame(r, 1)) * d[1] + T(frame(r, 2)) * d[2]);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& closest, const Eigen::Vector3d& normal, double weight,
                                     double spacing) {
    return new ceres::AutoDiffCostFunction<ClosenessResidual, 3, 3>(new ClosenessResidual(closest, normal, weight, spacing));
  }

  const Eigen::Vector3d c;
  const double scale;
  Eigen::Matrix3d frame;
};

}  // namespace pqlayout
