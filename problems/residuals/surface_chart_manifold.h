// The reference surface as the vertices' manifold (not a residual): a vertex parameter block
// lives ON the reference triangle mesh and moves along it, so closeness to the reference is a
// hard constraint, not a penalty that planarity can outweigh.
//   Plus(x, δ) = P(x + B_x δ)
// B_x: an orthonormal basis of the plane of the reference triangle that x lies on (tangent
// size 2), or for a vertex on the reference boundary the unit tangent of the boundary edge it
// lies on (tangent size 1); P: the closest point on the reference mesh (resp. its boundary
// polylines), i.e. the step is taken in the tangent plane and retracted onto the surface. At
// δ = 0 the Jacobian of Plus is B_x (P is the identity on the triangle's plane near x).
// Minus(y, x) = B_xᵀ (y − x), its first-order inverse.
// Every method needs the triangle (edge) under x, i.e. a closest-point query. The manifold
// (one per vertex) remembers its last two points with their triangles — the current state
// and the last candidate Plus produced, which are what Ceres asks about next (PlusJacobian
// at an accepted candidate, Plus again at a rejected one's start) — and hands the newest
// triangle to the query as a hint otherwise: 1 hinted query per Plus instead of 3 full ones.
// Ceres calls one parameter block's manifold from one thread at a time.
#pragma once

#include <ceres/manifold.h>

#include <Eigen/Core>

#include <array>

#include "geometry/closest_point.h"

namespace pqlayout {

class SurfaceManifold final : public ceres::Manifold {
 public:
  // query must outlive the manifold; on_boundary: slide along the boundary polylines.
  SurfaceManifold(const ClosestPointQuery* query, bool on_boundary) : query_(query), on_boundary_(on_boundary) {}

  int AmbientSize() const override { return 3; }
  int TangentSize() const override { return on_boundary_ ? 1 : 2; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const Eigen::Matrix<double, 3, 2> B = Basis(x);
    Eigen::Vector3d y = Eigen::Map<const Eigen::Vector3d>(x) + B.col(0) * delta[0];
    if (!on_boundary_) y += B.col(1) * delta[1];
    const SurfacePoint c = Project(y);
    Eigen::Map<Eigen::Vector3d> out(x_plus_delta);
    out = c.point;
    Remember(c);
    return true;
  }
  bool PlusJacobian(const double* x, double* jacobian) const override {
    const Eigen::Matrix<double, 3, 2> B = Basis(x);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < TangentSize(); ++c) jacobian[r * TangentSize() + c] = B(r, c);
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    const Eigen::Matrix<double, 3, 2> B = Basis(x);
    const Eigen::Vector3d d = Eigen::Map<const Eigen::Vector3d>(y) - Eigen::Map<const Eigen::Vector3d>(x);
    for (int c = 0; c < TangentSize(); ++c) y_minus_x[c] = B.col(c).dot(d);
    return true;
  }
  bool MinusJacobian(const double* x, double* jacobian) const override {
    const Eigen::Matrix<double, 3, 2> B = Basis(x);
    for (int c = 0; c < TangentSize(); ++c)
      for (int r = 0; r < 3; ++r) jacobian[c * 3 + r] = B(r, c);
    return true;
  }

  // The tangent basis at x (second column unused on the boundary).
  Eigen::Matrix<double, 3, 2> Basis(const double* x) const {
    const Eigen::Vector3d p(x[0], x[1], x[2]);
    Eigen::Matrix<double, 3, 2> B;
    const SurfacePoint& c = At(p);
    if (on_boundary_) {
      B.col(0) = c.tangent;
      B.col(1).setZero();
      return B;
    }
    const Eigen::Vector3d n = c.normal.normalized();
    const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    B.col(0) = n.cross(axis).normalized();
    B.col(1) = n.cross(B.col(0));
    return B;
  }

 private:
  SurfacePoint Project(const Eigen::Vector3d& p) const {
    const int hint = cache_[newest_].element;
    return on_boundary_ ? query_->OnBoundary(p, hint) : query_->OnSurface(p, hint);
  }
  void Remember(const SurfacePoint& c) const {
    newest_ ^= 1;
    cache_[newest_] = c;
  }
  // The closest point of p (p itself when p is on the reference), from the cache if p is one
  // of the last two points.
  const SurfacePoint& At(const Eigen::Vector3d& p) const {
    for (const int k : {newest_, newest_ ^ 1})
      if (cache_[k].element >= 0 && cache_[k].point == p) return cache_[k];
    SurfacePoint c = Project(p);
    c.point = p;  // the key: the point asked about
    Remember(c);
    return cache_[newest_];
  }

  const ClosestPointQuery* query_;
  const bool on_boundary_;
  mutable std::array<SurfacePoint, 2> cache_;
  mutable int newest_ = 0;
};

}  // namespace pqlayout
