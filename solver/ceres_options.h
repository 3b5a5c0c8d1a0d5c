// The one Ceres setup every nonlinear least-squares stage uses: Levenberg–Marquardt with
// sparse normal Cholesky through SuiteSparse (CHOLMOD), both cores, stop at a relative cost
// decrease of 1e-6, silent (stages log their own progress).
#pragma once

#include <ceres/ceres.h>

namespace pqlayout {

inline ceres::Solver::Options SparseCholeskyOptions(int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  options.num_threads = 2;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-6;
  options.logging_type = ceres::SILENT;
  return options;
}

}  // namespace pqlayout
