// The one Ceres setup every nonlinear least-squares stage uses: Levenberg–Marquardt with
// sparse normal Cholesky through Eigen's simplicial LDLᵀ, stop at a relative cost decrease
// of 1e-6, silent (stages log their own progress), on NumericThreads() threads (default 1),
// and abort on SIGINT/SIGTERM.
// Eigen's factorisation rather than CHOLMOD's: it is compiled code with no CPU-dispatched
// BLAS kernel, so the factor is bit-identical on every machine (solver/numerics.h), and on
// these problems (one scalar per vertex, ~10⁴ unknowns) it is also faster (README, timings).
#pragma once

#include <ceres/ceres.h>

#include "base/interrupt.h"
#include "solver/numerics.h"

namespace pqlayout {

// Ends a solve at the next iteration once SIGINT or SIGTERM has been received, or an
// embedding's poll asks to stop (base/interrupt.h): Ceres returns USER_FAILURE, whose solution is not usable, so the
// stage fails and the run ends as interrupted within one iteration. It also ends the solves of
// a thread whose own work was cancelled (ThreadCancelled: a solve alongside no longer wanted).
class InterruptCallback : public ceres::IterationCallback {
 public:
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return PollInterrupt() != 0 || ThreadCancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }
};

inline ceres::Solver::Options SparseCholeskyOptions(int max_iterations) {
  static InterruptCallback interrupt;  // stateless: one for every solve
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  options.num_threads = NumericThreads();
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-6;
  options.logging_type = ceres::SILENT;
  options.callbacks.push_back(&interrupt);  // first, so that it wins over a stage's own callbacks
  return options;
}

}  // namespace pqlayout
