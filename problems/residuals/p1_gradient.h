// The gradient of a P1 function on one face, for the residual functors: with the face's
// basis gradients G = [∇B_a ∇B_b ∇B_c] (3×3, constant on the face, see
// geometry/differential_operators.h) and the vertex values u_a, u_b, u_c,
// ∇u = u_a ∇B_a + u_b ∇B_b + u_c ∇B_c (a vector in the face's plane).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

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

// The signed sine of the crossing of φ and ψ on a face (transversality_residual.h, used also
// by crossing_barrier_residual.h): with the face's unit normal n and spacing h,
//   s = n · (∇φ × ∇ψ) / max(|∇φ| |∇ψ|, 1/h²).
template <typename T>
T SignedCrossingSine(const Eigen::Matrix3d& G, const Eigen::Vector3d& n, double h_squared, const T* phi_a,
                     const T* phi_b, const T* phi_c, const T* psi_a, const T* psi_b, const T* psi_c) {
  const Eigen::Matrix<T, 3, 1> gphi = P1Gradient(G, phi_a, phi_b, phi_c);
  const Eigen::Matrix<T, 3, 1> gpsi = P1Gradient(G, psi_a, psi_b, psi_c);
  const T lengths = SafeNorm(gphi) * SafeNorm(gpsi);
  const T denominator = lengths > T(1.0 / h_squared) ? lengths : T(1.0 / h_squared);
  return n.cast<T>().dot(gphi.cross(gpsi)) / denominator;
}

}  // namespace pqlayout
