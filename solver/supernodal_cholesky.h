// SupernodalCholesky: sparse LLᵀ of a large symmetric positive-definite matrix of scalar
// unknowns (the membrane's on a fine reference) by the multifrontal method (Duff & Reid 1983;
// Liu 1992, "The multifrontal method for sparse matrix solution") on relaxed supernodes, with
// dense kernels of our own (solver/front_kernels.h).
//
// Why our own and not CHOLMOD's: CHOLMOD factors either simplicially (one column at a time,
// ~1.1 GFlop/s: 4.3 s of the 962k-triangle Great Court's membrane, 4.9e9 flops) or
// supernodally on the BLAS, whose kernels OpenBLAS picks per CPU, so that the factor, and every
// stage after it, would differ in its last bits from one machine to the next (solver/numerics.h).
// Eigen has no supernodal Cholesky, and its dense products for dynamic sizes block their inner
// dimension by the CPU's cache sizes, which changes the order of the sums. Here every sum runs
// in an order fixed by the code: the same bits on every machine.
//
// Method: the rows ordered as given (e.g. NestedDissectionOrdering) and then by a postorder of
// the elimination tree (the same fill); column counts by row subtrees; fundamental supernodes,
// merged with their parent while the explicit zeros stay few (CHOLMOD's relaxation rules);
// then each supernode's frontal matrix assembled from A and its children's update matrices
// (extend-add), its pivot columns factored and the rest updated in panels (FactorFront). The
// two halves below the top separator on two threads (set_threads): the same bits as one.
#pragma once

#include <cstddef>
#include <thread>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "base/status.h"

namespace pqlayout {

// An array of doubles, not initialised, in transparent huge pages where the kernel offers them
// (madvise): L at 479k unknowns is ~400 MB, and in a virtual machine its 100k first-touch page
// faults of 4 KiB cost more than the arithmetic that fills it.
class LargeArray {
 public:
  LargeArray() = default;
  LargeArray(const LargeArray&) = delete;
  LargeArray& operator=(const LargeArray&) = delete;
  ~LargeArray();
  void Allocate(size_t size);  // the old contents are dropped
  double* data() { return data_; }
  const double* data() const { return data_; }

 private:
  double* data_ = nullptr;
  size_t size_ = 0;
};

class SupernodalCholesky {
 public:
  // Factors A (n × n, compressed, both triangles stored, symmetric) with the rows eliminated in
  // the order `perm` (perm[k] = the row eliminated k-th; refined by the elimination tree's
  // postorder). InvalidInput if A is not square, perm not a permutation of its rows, or an entry
  // not finite; Internal if A is not positive definite (failed_row() names the row, in A's
  // numbering).
  Status Factorize(const Eigen::SparseMatrix<double>& A, const std::vector<int>& perm);
  // Solves A x = b with the last successful factorisation.
  Status Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const;

  int failed_row() const { return failed_row_; }
  double flops() const { return flops_; }        // of the last factorisation (multiply-adds × 2, explicit zeros included)
  double nonzeros() const { return nonzeros_; }  // stored entries of L, explicit zeros included
  int supernodes() const { return static_cast<int>(first_.size()) - 1; }
  // Threads for Factorize: 2 (default, where the machine has 2 hardware threads or more) factors
  // the two halves below the top separator side by side; 1 does all on the calling thread. The
  // same bits either way (FactorizeNumeric).
  void set_threads(int threads) { threads_ = threads; }
  // Supernodes of the last factorisation factored on the second thread (0: one thread).
  int second_thread_supernodes() const { return second_thread_supernodes_; }

 private:
  struct Lower {  // the permuted matrix's lower triangle, by columns
    std::vector<int> outer, inner;
    std::vector<double> values;
  };
  Lower Permuted(const Eigen::SparseMatrix<double>& A) const;
  void Analyze(const Lower& C);                 // supernodes and their row structures
  Status FactorizeNumeric(const Lower& C);
  struct Workspace;
  void FactorSupernodes(const Lower& C, const std::vector<std::vector<int>>& kids, const std::vector<int>& nodes,
                        std::vector<const double*>* update, Workspace* w);

  int n_ = 0;
  bool factorized_ = false;
  int failed_row_ = -1;
  int threads_ = std::thread::hardware_concurrency() >= 2 ? 2 : 1;
  int second_thread_supernodes_ = 0;
  double flops_ = 0.0, nonzeros_ = 0.0;
  std::vector<int> perm_, inverse_;             // final: new → old row, old → new
  std::vector<int> first_;                      // supernode s: columns first_[s] … first_[s + 1] − 1
  std::vector<int> parent_;                     // supernode s's parent supernode, or −1
  std::vector<std::vector<int>> rows_;          // supernode s's rows below its columns (sorted)
  std::vector<size_t> offset_;                  // supernode s's columns of L: factor_[offset_[s] …], (ns + |rows|) × ns, column-major
  LargeArray factor_;
};

}  // namespace pqlayout
