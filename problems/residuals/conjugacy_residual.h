// Conjugacy (per face f): the level-line tangents t1 = n × ∇φ and t2 = n × ∇ψ are conjugate
// with respect to the face's shape operator S, II(t1, t2) = t1ᵀ S t2 = 0, which is what makes
// the quads of the extracted mesh nearly planar (Liu et al. 2006; Zadravec et al. 2010):
//   r_f = √A_f · t1ᵀ S̃ t2 / (|t1| |t2| κ̃_f),   S̃ = S + μ P,   κ̃_f = |κ1| + |κ2| + μ
// Normalised so that it is scale free (a pure function of the directions: invariant under
// scaling the surface, φ or ψ). μ (1/m) makes the term fall back smoothly to orthogonality,
// t1 ⊥ t2, where the surface is flat and the conjugate direction is undefined.
// Parameters: φ at the face's three vertices, then ψ at the same vertices.
#pragma once

#include <ceres/ceres.h>

#include <cmath>

#include "problems/residuals/p1_gradient.h"

namespace pqlayout {

struct ConjugacyResidual {
  ConjugacyResidual(const Eigen::Matrix3d& basis_gradients, const Eigen::Vector3d& normal,
                    const Eigen::Matrix3d& shape_operator, double flat_curvature, double area)
      : G(basis_gradients), n(normal), S_reg(Regularised(shape_operator, normal, flat_curvature)),
        scale(std::sqrt(area) / (CurvatureSum(shape_operator, normal) + flat_curvature)) {}

  template <typename T>
  bool operator()(const T* const phi_a, const T* const phi_b, const T* const phi_c, const T* const psi_a,
                  const T* const psi_b, const T* const psi_c, T* residual) const {
    const Eigen::Matrix<T, 3, 1> nT = n.cast<T>();
    const Eigen::Matrix<T, 3, 1> t1 = nT.cross(P1Gradient(G, phi_a, phi_b, phi_c));
    const Eigen::Matrix<T, 3, 1> t2 = nT.cross(P1Gradient(G, psi_a, psi_b, psi_c));
    const T lengths = SafeNorm(t1) * SafeNorm(t2);
    if (!(lengths > T(0.0))) {
      residual[0] = T(0.0);
      return true;
    }
    residual[0] = T(scale) * t1.dot(S_reg.cast<T>() * t2) / lengths;
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Matrix3d& basis_gradients, const Eigen::Vector3d& normal,
                                     const Eigen::Matrix3d& shape_operator, double flat_curvature, double area) {
    return new ceres::AutoDiffCostFunction<ConjugacyResidual, 1, 1, 1, 1, 1, 1, 1>(
        new ConjugacyResidual(basis_gradients, normal, shape_operator, flat_curvature, area));
  }

  // S + μ P: conjugacy where curved, orthogonality where flat.
  static Eigen::Matrix3d Regularised(const Eigen::Matrix3d& S, const Eigen::Vector3d& n, double mu) {
    return S + mu * (Eigen::Matrix3d::Identity() - n * n.transpose());
  }
  // |κ1| + |κ2| of a tangent symmetric S: the nuclear norm of its 2×2 restriction.
  static double CurvatureSum(const Eigen::Matrix3d& S, const Eigen::Vector3d& n) {
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
    const Eigen::Matrix3d M = P * (0.5 * (S + S.transpose())) * P;
    const double trace = M.trace();
    const double det2 = 0.5 * (trace * trace - (M * M).trace());  // κ1 κ2
    const double disc = std::sqrt(std::max(0.0, trace * trace - 4.0 * det2));
    return std::abs(0.5 * (trace + disc)) + std::abs(0.5 * (trace - disc));
  }

  const Eigen::Matrix3d G;
  const Eigen::Vector3d n;
  const Eigen::Matrix3d S_reg;
  const double scale;
};

}  // namespace pqlayout
