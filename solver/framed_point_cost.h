// A Ceres cost function whose 3-vector point inputs are seen through per-point local
// frames: inner(…, p, …) with p = o + R q, where q is the parameter block Ceres moves and
// (o, R) a fixed origin and rotation; Jacobians chained, ∂r/∂q = ∂r/∂p · R. Blocks without a
// frame (nullptr) pass through unchanged (e.g. a face's plane).
// Why: `stiffen` bounds each vertex inside a box of its own frame (tangent, tangent, normal
// of the reference at its foot point), which Ceres' axis-aligned parameter bounds can only
// express on q, while the residual functors (planarity, fairness, edge length) are written
// on world points and stay as they are.
#pragma once

#include <ceres/ceres.h>

#include <memory>
#include <vector>

#include <Eigen/Core>

namespace pqlayout {

struct PointFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: the local axes in world coordinates
  Eigen::Vector3d ToWorld(const Eigen::Vector3d& q) const { return origin + rotation * q; }
  Eigen::Vector3d ToLocal(const Eigen::Vector3d& p) const { return rotation.transpose() * (p - origin); }
};

class FramedPointCost : public ceres::CostFunction {
 public:
  // Takes ownership of inner; frames[k] (not owned, may be nullptr) maps parameter block k,
  // which must then have size 3.
  FramedPointCost(ceres::CostFunction* inner, std::vector<const PointFrame*> frames)
      : inner_(inner), frames_(std::move(frames)) {
    set_num_residuals(inner_->num_residuals());
    *mutable_parameter_block_sizes() = inner_->parameter_block_sizes();
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const size_t n = frames_.size();
    std::vector<Eigen::Vector3d> mapped(n);
    std::vector<const double*> pointers(parameters, parameters + n);
    for (size_t k = 0; k < n; ++k) {
      if (frames_[k] == nullptr) continue;
      mapped[k] = frames_[k]->ToWorld(Eigen::Map<const Eigen::Vector3d>(parameters[k]));
      pointers[k] = mapped[k].data();
    }
    if (!inner_->Evaluate(pointers.data(), residuals, jacobians)) return false;
    if (jacobians == nullptr) return true;
    const int m = num_residuals();
    for (size_t k = 0; k < n; ++k) {
      if (jacobians[k] == nullptr || frames_[k] == nullptr) continue;
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> J(jacobians[k], m, 3);
      J = (J * frames_[k]->rotation).eval();
    }
    return true;
  }

 private:
  std::unique_ptr<ceres::CostFunction> inner_;
  std::vector<const PointFrame*> frames_;
};

}  // namespace pqlayout
