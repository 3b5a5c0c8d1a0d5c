// Planarity as the manifold that stiffen's L-BFGS walks on (problems/stiffen.h): the set
// {z : δ(sub-quad) ≤ δ_allowed for every sub-quad of every face} in the box variables z
// (problems/stiffen_problem.h), as a ceres::Manifold of Ceres' GradientProblemSolver.
//   - tangent: the gradient and every step are projected on the null space of the active
//     constraints' Jacobian J (rows s_k ∇δ_s,k, s_k = sign δ_s,k, for the sub-quads with
//     δ ≥ (1 − band) δ_allowed):  P v = v − Jᵀ (J Jᵀ)⁻¹ J v  (J Jᵀ by CHOLMOD). A constraint
//     whose multiplier says the objective pulls it inside is released first (y = (J Jᵀ)⁻¹ J g,
//     y_k > 0: moving along −g lowers δ_k), so faces can give back planarity budget.
//   - retraction: z + P Δ, then min-norm Gauss–Newton steps z ← z − J_Vᵀ (J_V J_Vᵀ)⁻¹ c_V on
//     the violated sub-quads V (c = |δ_s| − δ_allowed) until max c ≤ 1e-3 δ_allowed.
// Why: as a penalty (the augmented Lagrangian this replaces) the planarity of thousands of
// sub-quads makes the Lagrangian's Hessian ill-conditioned: the only moves that keep every
// panel planar are long-range (a whole mesh polyline, the discrete f(u) + g(v) twist-free
// offsets), which L-BFGS had to find through ρ JᵀJ and at h = 1.25 m did not (C × 0.92 against
// × 0.74 at h = 3 m). Projected, L-BFGS sees only the compliance's own curvature.
// The projection changes with z, so Ceres' L-BFGS pairs are those of a Riemannian L-BFGS
// without vector transport, which is enough when the constraints bend slowly.
#pragma once

#include <ceres/manifold.h>

#include <deque>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/SparseCore>

#include "problems/stiffen_problem.h"

namespace pqlayout {

class CholmodSolver;

class PlanarityManifold final : public ceres::Manifold {
 public:
  PlanarityManifold(const StiffenProblem& P, const BoxVariables& box, double allowed);
  ~PlanarityManifold() override;

  int AmbientSize() const override { return box_.size(); }
  int TangentSize() const override { return box_.size(); }
  bool Plus(const double* z, const double* delta, double* z_plus_delta) const override;
  // Never formed (N × N dense); Ceres' GradientProblem only calls RightMultiplyByPlusJacobian.
  bool PlusJacobian(const double*, double*) const override { return false; }
  bool RightMultiplyByPlusJacobian(const double* z, int num_rows, const double* ambient,
                                   double* tangent) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double*, double*) const override { return false; }

  // Moves z onto the constraint set; false if the violation is still above 1e-3 δ_allowed.
  bool Retract(double* z) const;
  // Raises each sub-quad's δ_allowed to its |δ| at z where that is higher, so that z (a start
  // that Retract could not bring within δ_allowed) lies on the constraint set: those sub-quads
  // may then not get less planar than they start, the others keep δ_allowed. Returns how many
  // were raised. Why: planarize stops at δ ≤ target, stiffen asks 0.9 × target, and where
  // the retraction fails to close that gap (a 15-iteration joint solve on the wavy roof ×
  // curvature: δ 0.000955 on a folded panel cut into triangles) stiffen used to run nothing.
  int AdmitStart(const double* z);
  int active() const;  // size of the last active set
  int incomplete_retractions() const { return incomplete_retractions_; }

 private:
  struct Linearisation;
  std::vector<double> Values(const double* z) const;  // δ_s of every constraint
  // J of the given rows at the points x (row r: sign(δ_s) ∂δ_s/∂x · dx(k, c) per free coordinate
  // (k, c) not frozen) and its factorised Gram matrix J Jᵀ + regularisation × its diagonal.
  std::unique_ptr<Linearisation> Linearise(const std::vector<Eigen::Vector3d>& x, const std::vector<int>& rows,
                                           const std::vector<double>& values,
                                           const std::function<Eigen::Vector3d(int, int)>& dx,
                                           const std::vector<bool>* frozen, double regularisation) const;
  const Linearisation& At(const double* z, const double* gradient) const;
  void Project(const Linearisation& A, const double* v, double* out) const;

  const StiffenProblem& P_;
  const BoxVariables& box_;
  std::vector<double> allowed_;   // δ_allowed per constraint (AdmitStart raises some)
  std::vector<int> constraints_;  // sub-quads with a free vertex
  std::unique_ptr<ceres::CostFunction> delta_;
  mutable std::deque<std::unique_ptr<Linearisation>> cache_;
  mutable int incomplete_retractions_ = 0;  // the last few points' active sets
};

}  // namespace pqlayout
