// Shared finite-difference check of a Ceres cost function (ceres::GradientChecker), used by
// the tests of every residual functor.
#pragma once

#include <gtest/gtest.h>
#include <ceres/gradient_checker.h>

#include <memory>
#include <string>
#include <vector>

namespace pqlayout::testing {

// Probes `cost` (takes ownership) at the parameter blocks' values. Ridders' extrapolation
// starts from 0.01 % of |x| (the default 1 % is too coarse where normalised terms curve
// sharply), and Jacobians must match to 1e-7 relative.
inline void ExpectJacobiansMatchFiniteDifferences(const std::string& name, ceres::CostFunction* cost,
                                                  const std::vector<std::vector<double>>& blocks,
                                                  const std::vector<const ceres::Manifold*>* manifolds = nullptr) {
  SCOPED_TRACE(name);
  std::unique_ptr<ceres::CostFunction> owned(cost);
  std::vector<const double*> pointers;
  for (const auto& b : blocks) pointers.push_back(b.data());
  ceres::NumericDiffOptions options;
  options.ridders_relative_initial_step_size = 1e-4;
  ceres::GradientChecker checker(owned.get(), manifolds, options);
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(pointers.data(), 1e-7, &results)) << results.error_log;
}

// The same for functors whose parameter blocks are all scalars.
inline void ExpectJacobiansMatchFiniteDifferences(const std::string& name, ceres::CostFunction* cost,
                                                  const std::vector<double>& scalars) {
  std::vector<std::vector<double>> blocks;
  for (const double x : scalars) blocks.push_back({x});
  ExpectJacobiansMatchFiniteDifferences(name, cost, blocks);
}

}  // namespace pqlayout::testing
