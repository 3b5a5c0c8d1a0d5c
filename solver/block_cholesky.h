// BlockCholesky: sparse LLᵀ factorisation of a symmetric positive-definite matrix made of 6 × 6
// node blocks (a frame's stiffness, six DOFs per node), with dense fixed-size block kernels.
//
// Why our own and not CHOLMOD's: CHOLMOD factors a frame either simplicially (scalar, one
// column at a time: ~0.75–2 GFlop/s on the Great Court's frame, 61 % of a stiffen iteration) or
// supernodally on the BLAS, whose kernels OpenBLAS picks per CPU, so that the factor, and with it
// every later stiffen step, differs in its last bits from one machine to the next
// (solver/numerics.h). Eigen has no supernodal Cholesky. Here every block operation is Eigen's
// 6 × 6 code, compiled once with the program's flags: the same bits on every machine.
//
// Method: the node graph ordered by Eigen's approximate minimum degree, the block elimination
// tree and the column structures of L computed once per pattern (Analyze), then a left-looking
// block factorisation (Factorize) and block forward / back substitution (Solve).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "base/status.h"

namespace pqlayout {

class BlockCholesky {
 public:
  static constexpr int kBlock = 6;
  using Block = Eigen::Matrix<double, kBlock, kBlock>;

  // Analyses A's node pattern (A: 6n × 6n, compressed, both triangles stored) unless A has the
  // scalar pattern of the last analysis, then factors A. InvalidInput if A is not square of a
  // multiple of 6 rows or has an entry that is not finite (failed_row() its row);
  // Internal if it is not positive definite (failed_row() then names the first row of the node
  // block that failed, in A's numbering).
  Status Factorize(const Eigen::SparseMatrix<double>& A);

  // Solves A x = b with the last successful factorisation.
  Status Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const;

  int failed_row() const { return failed_row_; }
  // (min / max of L's diagonal)², as CHOLMOD estimates the reciprocal condition number of LLᵀ.
  double rcond() const { return rcond_; }
  bool factorized() const { return factorized_; }

 private:
  void Analyze();  // of pattern_

  int nodes_ = 0;
  bool factorized_ = false;
  int failed_row_ = -1;
  double rcond_ = 0.0;
  std::vector<int> perm_, inverse_;            // new → old node, old → new
  std::vector<int> outer_, inner_;             // the analysed matrix's scalar pattern, as stored
  std::vector<std::vector<int>> pattern_;      // its node pattern: per old node, its neighbours (sorted)
  std::vector<std::vector<int>> rows_;         // per new column j: the rows i > j of L's blocks (sorted)
  std::vector<std::vector<std::pair<int, int>>> row_entries_;  // per new row j: (column k, slot in rows_[k])
  std::vector<Block> diagonal_;                // L_jj (lower)
  std::vector<std::vector<Block>> below_;      // L_ij, i in rows_[j]
};

}  // namespace pqlayout
