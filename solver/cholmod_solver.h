// CholmodSolver: sparse symmetric positive-definite solves with CHOLMOD (Davis & Hager).
// With one numeric thread (the default) the factorisation is simplicial (LLᵀ, no BLAS),
// not supernodal as the paper's §2.2 suggests: it gives the same factor on every CPU, which
// the supernodal one, running on OpenBLAS's CPU-specific kernels, does not; with more
// threads CHOLMOD picks supernodal where it pays (solver/numerics.h; timings in
// benchmarks/RESULTS.md). The CHOLMOD context lives behind RAII; input is checked (square, finite,
// symmetric) before factoring, and failures are reported as a Status, never as an abort.
// Usage: Factorize once, Solve many times (precompute / solve split).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "base/status.h"

struct cholmod_sparse_struct;  // cholmod.h

namespace pqlayout {

class CholmodSolver {
 public:
  CholmodSolver();
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  // Analyses and factors A (n by n, symmetric positive definite; both triangles stored).
  // InvalidInput if A is not square, not finite or not symmetric; Internal if it is not
  // positive definite (the message names the failing column). With reuse_analysis, a matrix
  // with exactly the previous one's sparsity pattern keeps its symbolic analysis (fill-
  // reducing ordering), and only the numeric factorisation is redone (stiffen's iterations).
  Status Factorize(const Eigen::SparseMatrix<double>& A, bool reuse_analysis = false);

  // The fill-reducing ordering of the next analyses (perm[k] = the row eliminated k-th, e.g.
  // NestedDissectionOrdering); empty (the default): CHOLMOD's own choice (AMD, or METIS where
  // AMD's factor would be dense). Factorize refuses a perm that is not a permutation of A's rows.
  void SetOrdering(std::vector<int> perm);

  // Solves A x = b with the last successful factorisation (b: n by k).
  Status Solve(const Eigen::MatrixXd& b, Eigen::MatrixXd* x) const;
  Status Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const;

  bool factorized() const;
  bool is_supernodal() const;
  int rows() const { return rows_; }
  // After a failed Factorize: the row/column of A (original numbering) where the Cholesky
  // factorisation broke down, or -1. Callers map it back to a vertex or node.
  int failed_row() const { return failed_row_; }
  // Reciprocal condition number estimate of the last factorisation (CHOLMOD's rcond).
  double rcond() const { return rcond_; }
  // The last analysis's nonzeros in L and floating-point operations of the factorisation.
  double factor_nonzeros() const;
  double factor_flops() const;

 private:
  Status Analyze(cholmod_sparse_struct* A, long n);
  struct Impl;
  std::unique_ptr<Impl> impl_;  // also the pattern of the analysed matrix
  int rows_ = 0;
  int failed_row_ = -1;
  double rcond_ = 0.0;
};

}  // namespace pqlayout
