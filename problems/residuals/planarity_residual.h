// Planarity (per face f and each of its vertices v): the vertex lies on the face's plane
// {x : n_f · x = d_f}, with an auxiliary unit normal n_f (on Ceres' SphereManifold<3>) and
// offset d_f per face:
//   r_fv = √w · (n_f · p_v − d_f) / ℓ_f
// ℓ_f = the face's mean diagonal length, so r ≈ the SPEC planarity δ (scale free). Chosen
// over the diagonal-distance form because each residual is linear in p_v and bilinear in
// (n_f, p_v): Gauss–Newton converges in few iterations even for n-gons (Liu et al. 2006 use
// the same auxiliary-plane idea; Tang et al. 2014 for its speed).
// Parameters: n_f (3), d_f (1), p_v (3).
#pragma once

#include <ceres/ceres.h>

#include <cmath>

namespace pqlayout {

struct PlanarityResidual {
  PlanarityResidual(double weight, double mean_diagonal) : scale(std::sqrt(weight) / mean_diagonal) {}

  template <typename T>
  bool operator()(const T* const n, const T* const d, const T* const p, T* residual) const {
    residual[0] = T(scale) * (n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - d[0]);
    return true;
  }

  static ceres::CostFunction* Create(double weight, double mean_diagonal) {
    return new ceres::AutoDiffCostFunction<PlanarityResidual, 1, 3, 1, 3>(new PlanarityResidual(weight, mean_diagonal));
  }

  const double scale;
};

}  // namespace pqlayout
