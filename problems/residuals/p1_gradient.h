// The gradient of a P1 function on one face, for the residual functors: with the face's
// basis gradients G = [∇B_a ∇B_b ∇B_c] (3×3, constant on the face, see
// geometry/differential_operators.h) and the vertex values u_a, u_b, u_c,
// ∇u = u_a ∇B_a + u_b ∇B_b + u_c ∇B_c (a vector in the face's plane).
#pragma once

#include <Eigen/Core>

namespace pqlayout {

template <typename T>
Eigen::Matrix<T, 3, 1> P1Gradient(const Eigen::Matrix3d& G, const T* a, const T* b, const T* c) {
  return G.col(0).cast<T>() * a[0] + G.col(1).cast<T>() * b[0] + G.col(2).cast<T>() * c[0];
}

// |v| for autodiff, finite at v = 0 (where the true derivative is undefined).
template <typename T>
T SafeNorm(const Eigen::Matrix<T, 3, 1>& v) {
  const T squared = v.squaredNorm();
  return squared > T(1e-300) ? sqrt(squared) : T(0.0);
}

}  // namespace pqlayout
