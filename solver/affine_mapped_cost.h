// A Ceres cost function over scalar parameter blocks that the inner cost function sees
// through affine maps: inner(x'₁, …, x'ₙ) with x'ₖ = sₖ·xₖ + aₖ, Jacobians chained
// (∂r/∂xₖ = sₖ·∂r/∂x'ₖ). This is how a level-set function that jumps across a seam,
// u₊ = s·u₋ + a, stays one unknown per seam vertex: the faces on the plus side read the minus
// copy's parameter through the map, so the transition holds exactly (no penalty to balance
// against the other terms) and the inner functors need not know about seams.
// Ceres has no built-in for this: a Manifold maps one block to itself, not one block into
// several residuals' different charts.
#pragma once

#include <ceres/ceres.h>

#include <memory>
#include <vector>

namespace pqlayout {

class AffineMappedCost : public ceres::CostFunction {
 public:
  // Takes ownership of inner, whose parameter blocks must all have size 1.
  AffineMappedCost(ceres::CostFunction* inner, std::vector<double> scale, std::vector<double> offset)
      : inner_(inner), scale_(std::move(scale)), offset_(std::move(offset)) {
    set_num_residuals(inner_->num_residuals());
    *mutable_parameter_block_sizes() = inner_->parameter_block_sizes();
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const size_t n = scale_.size();
    std::vector<double> mapped(n);
    std::vector<const double*> pointers(n);
    for (size_t k = 0; k < n; ++k) {
      mapped[k] = scale_[k] * parameters[k][0] + offset_[k];
      pointers[k] = &mapped[k];
    }
    if (!inner_->Evaluate(pointers.data(), residuals, jacobians)) return false;
    if (jacobians != nullptr)
      for (size_t k = 0; k < n; ++k)
        if (jacobians[k] != nullptr)
          for (int r = 0; r < num_residuals(); ++r) jacobians[k][r] *= scale_[k];
    return true;
  }

 private:
  std::unique_ptr<ceres::CostFunction> inner_;
  std::vector<double> scale_, offset_;
};

}  // namespace pqlayout
