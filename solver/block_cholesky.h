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
//
// Two threads where the machine has them (stiffen's frame is factored at every evaluation, and
// the stage otherwise leaves the second core idle): a left-looking column reads only its
// descendants in the elimination tree, so disjoint subtrees can be factored side by side.
// Analyze deals subtrees to the two threads (splitting the heaviest, by the block products it
// needs, while the larger share plus what is left above shrinks), then the columns above them
// one by one to whichever thread has less work so far. Each thread factors its columns in
// ascending order and, before the update from a column of the other's, waits until that column
// is finished (no deadlock: the lowest unfinished column never waits). Each column is computed by
// the same code from the same finished columns in the same order whichever thread runs it: the
// same bits on any number of threads (test BlockCholesky.TwoThreadsGiveTheSameBitsAsOne). A
// factor that fails is run again on one thread, so that the block named is the one a single
// thread meets first.
#pragma once

#include <atomic>
#include <thread>
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

  // 2 (default where the machine has 2 hardware threads or more): a second thread (above); 1:
  // every column on the calling thread. The result is the same to the bit (the order and the plan
  // are the same either way).
  void set_threads(int threads) { threads_ = threads; }
  // Columns (node blocks) of the last analysis factored on the second thread (0: one thread).
  int second_thread_columns() const { return threads_ >= 2 ? static_cast<int>(columns_[1].size()) : 0; }

  int failed_row() const { return failed_row_; }
  // (min / max of L's diagonal)², as CHOLMOD estimates the reciprocal condition number of LLᵀ.
  double rcond() const { return rcond_; }
  bool factorized() const { return factorized_; }

 private:
  struct Scratch;
  void Analyze();  // of pattern_
  void Structure(std::vector<int> perm);  // perm_, inverse_, rows_ and row_entries_ for this order
  void PlanSplit();  // columns_, from rows_ and row_entries_
  // Factors the given columns (new numbering, ascending) with scratch s; false at the first that
  // is not positive definite (s->failed: that column). With two threads, done marks the finished
  // columns (each waits for the other's where it needs one) and stop the other's failure.
  bool FactorColumns(const Eigen::SparseMatrix<double>& A, const std::vector<int>& columns, Scratch* s,
                     std::atomic<char>* done = nullptr, std::atomic<bool>* stop = nullptr);

  int nodes_ = 0;
  bool factorized_ = false;
  int failed_row_ = -1;
  double rcond_ = 0.0;
  std::vector<int> perm_, inverse_;            // new → old node, old → new
  std::vector<int> outer_, inner_;             // the analysed matrix's scalar pattern, as stored
  std::vector<std::vector<int>> pattern_;      // its node pattern: per old node, its neighbours (sorted)
  std::vector<std::vector<int>> rows_;         // per new column j: the rows i > j of L's blocks (sorted)
  std::vector<std::vector<std::pair<int, int>>> row_entries_;  // per new row j: (column k, slot in rows_[k])
  std::vector<int> columns_[2];                // each thread's columns, ascending (empty: one thread)
  int threads_ = std::thread::hardware_concurrency() >= 2 ? 2 : 1;
  std::vector<Block> diagonal_;                // L_jj (lower)
  std::vector<std::vector<Block>> below_;      // L_ij, i in rows_[j]
};

}  // namespace pqlayout
