// Planarity (per face f and each of its vertices v): the vertex lies on the face's plane
// {x : n_f · (x − c_f) = d_f}, with an auxiliary plane per face — unit normal n_f and offset
// d_f in one parameter block (n_f on Ceres' SphereManifold<3>, d_f Euclidean):
//   r_fv = √w · (n_f · (p_v − c_f) − d_f) / ℓ_f
// ℓ_f = the face's mean diagonal length, so r ≈ the SPEC planarity δ (scale free); c_f a fixed
// point near the face (its centroid where the plane was fitted). Measured from c_f, a turn of
// n_f turns the plane about the face, not about the origin: with the offset measured from the
// origin (n_f · p_v − d_f) the Jacobian's n-columns are the vertices' coordinates, so the
// normal equations' (n, d) block had a condition number ~ (|p| / ℓ)², and a strip of quads
// 5 km from the origin ended 0.58 m from the same strip planarised at the origin
// (benchmarks/RESULTS.md, "Planes measured from their faces").
// Why this form: each residual is linear in p_v and bilinear in (plane, p_v), so
// Gauss–Newton converges in few iterations even for n-gons (Liu et al. 2006 use the same
// auxiliary-plane idea), where the diagonal-distance form is a ratio of cross products with
// a badly scaled Jacobian near planarity; and no residual couples two planes, so the planes
// are an independent set that Ceres' Schur complement eliminates (problems/planarize.cc,
// SetStepSolver: each step is solved over the vertices only).
// Parameters: plane = (n_f, d_f) (4), p_v (3); c_f is a constant.
#pragma once

#include <ceres/ceres.h>
#include <Eigen/Core>

#include <cmath>

namespace pqlayout {

struct PlanarityResidual {
  PlanarityResidual(double weight, double mean_diagonal, const Eigen::Vector3d& centre)
      : scale(std::sqrt(weight) / mean_diagonal), c(centre) {}

  template <typename T>
  bool operator()(const T* const plane, const T* const p, T* residual) const {
    residual[0] = T(scale) * (plane[0] * (p[0] - c[0]) + plane[1] * (p[1] - c[1]) + plane[2] * (p[2] - c[2]) - plane[3]);
    return true;
  }

  static ceres::CostFunction* Create(double weight, double mean_diagonal, const Eigen::Vector3d& centre) {
    return new ceres::AutoDiffCostFunction<PlanarityResidual, 1, 4, 3>(new PlanarityResidual(weight, mean_diagonal, centre));
  }

  const double scale;
  const Eigen::Vector3d c;
};

}  // namespace pqlayout
