// BlockCholesky: see solver/block_cholesky.h.
#include "solver/block_cholesky.h"

#include <Eigen/Cholesky>
#include <Eigen/OrderingMethods>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pqlayout {

namespace {

// Per node of A (old numbering): its neighbouring nodes, itself included, sorted.
std::vector<std::vector<int>> NodePattern(const Eigen::SparseMatrix<double>& A, int nodes) {
  std::vector<std::vector<int>> pattern(nodes);
  for (int col = 0; col < A.outerSize(); ++col) {
    std::vector<int>& around = pattern[col / BlockCholesky::kBlock];
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it)
      around.push_back(static_cast<int>(it.row()) / BlockCholesky::kBlock);
  }
  for (int c = 0; c < nodes; ++c) {
    pattern[c].push_back(c);
    std::sort(pattern[c].begin(), pattern[c].end());
    pattern[c].erase(std::unique(pattern[c].begin(), pattern[c].end()), pattern[c].end());
  }
  return pattern;
}

}  // namespace

void BlockCholesky::Analyze() {
  // Approximate minimum degree on the node graph (Eigen's AMD: integer code, the same order on
  // every machine).
  std::vector<Eigen::Triplet<int>> entries;
  for (int c = 0; c < nodes_; ++c)
    for (const int r : pattern_[c]) entries.emplace_back(r, c, 1);
  Eigen::SparseMatrix<int> graph(nodes_, nodes_);
  graph.setFromTriplets(entries.begin(), entries.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(graph, order);
  perm_.assign(order.indices().data(), order.indices().data() + nodes_);
  inverse_.assign(nodes_, 0);
  for (int j = 0; j < nodes_; ++j) inverse_[perm_[j]] = j;
  // The column structures of L: column j holds A's rows below j and its children's rows below j;
  // its parent in the elimination tree is the first of them.
  rows_.assign(nodes_, {});
  std::vector<std::vector<int>> children(nodes_);
  for (int j = 0; j < nodes_; ++j) {
    std::vector<int>& s = rows_[j];
    for (const int o : pattern_[perm_[j]])
      if (inverse_[o] > j) s.push_back(inverse_[o]);
    for (const int c : children[j])
      for (const int i : rows_[c])
        if (i > j) s.push_back(i);
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    if (!s.empty()) children[s.front()].push_back(j);
  }
  row_entries_.assign(nodes_, {});
  for (int k = 0; k < nodes_; ++k)
    for (int q = 0; q < static_cast<int>(rows_[k].size()); ++q) row_entries_[rows_[k][q]].push_back({k, q});
  diagonal_.assign(nodes_, Block::Zero());
  below_.assign(nodes_, {});
  for (int j = 0; j < nodes_; ++j) below_[j].assign(rows_[j].size(), Block::Zero());
}

Status BlockCholesky::Factorize(const Eigen::SparseMatrix<double>& A) {
  factorized_ = false;
  failed_row_ = -1;
  if (A.rows() != A.cols() || A.rows() % kBlock != 0)
    return Status::InvalidInput("block Cholesky: the matrix is " + std::to_string(A.rows()) + " × " +
                                std::to_string(A.cols()) + ", not square in 6 × 6 blocks");
  if (!A.isCompressed()) return Status::InvalidInput("block Cholesky: the matrix is not compressed");
  for (int col = 0; col < A.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it)
      if (!std::isfinite(it.value())) {
        failed_row_ = static_cast<int>(it.row());
        return Status::InvalidInput("block Cholesky: entry (" + std::to_string(it.row()) + ", " + std::to_string(col) +
                                    ") is not finite");
      }
  // The same scalar pattern as the last analysis (compared as stored: cheap): its analysis holds.
  const int nodes = static_cast<int>(A.rows()) / kBlock;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  if (nodes != nodes_ || outer_.size() != static_cast<size_t>(A.outerSize()) + 1 ||
      inner_.size() != static_cast<size_t>(A.nonZeros()) || !std::equal(outer_.begin(), outer_.end(), outer) ||
      !std::equal(inner_.begin(), inner_.end(), inner)) {
    nodes_ = nodes;
    outer_.assign(outer, outer + A.outerSize() + 1);
    inner_.assign(inner, inner + A.nonZeros());
    pattern_ = NodePattern(A, nodes);
    Analyze();
  }
  std::vector<int> slot(nodes_, -1);  // row node (new) → its place in the column being factored
  Block work_diagonal;
  std::vector<Block> work;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (int j = 0; j < nodes_; ++j) {
    const std::vector<int>& rows = rows_[j];
    for (int s = 0; s < static_cast<int>(rows.size()); ++s) slot[rows[s]] = s;
    work_diagonal.setZero();
    work.assign(rows.size(), Block::Zero());
    // Column j of A, its lower part in the new numbering.
    const int old = perm_[j];
    for (int c = 0; c < kBlock; ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, kBlock * old + c); it; ++it) {
        const int i = inverse_[static_cast<int>(it.row()) / kBlock], r = static_cast<int>(it.row()) % kBlock;
        if (i == j) work_diagonal(r, c) = it.value();
        else if (i > j) work[slot[i]](r, c) = it.value();
      }
    // Left-looking: minus L_*k L_jkᵀ for every column k < j with a block in row j.
    for (const auto& [k, p] : row_entries_[j]) {
      const Block ljk_t = below_[k][p].transpose();
      work_diagonal.noalias() -= below_[k][p] * ljk_t;
      for (int q = p + 1; q < static_cast<int>(rows_[k].size()); ++q)
        work[slot[rows_[k][q]]].noalias() -= below_[k][q] * ljk_t;
    }
    const Eigen::LLT<Block> llt(work_diagonal);
    if (llt.info() != Eigen::Success) {
      failed_row_ = kBlock * old;
      return Status::Internal("block Cholesky: not positive definite at node block " + std::to_string(old));
    }
    diagonal_[j] = llt.matrixL();
    for (int s = 0; s < static_cast<int>(rows.size()); ++s)
      below_[j][s] = diagonal_[j].triangularView<Eigen::Lower>().solve(work[s].transpose()).transpose();
    for (int d = 0; d < kBlock; ++d) lo = std::min(lo, diagonal_[j](d, d)), hi = std::max(hi, diagonal_[j](d, d));
    for (const int i : rows) slot[i] = -1;
  }
  rcond_ = nodes_ > 0 ? (lo / hi) * (lo / hi) : 0.0;
  factorized_ = true;
  return Status::Ok();
}

Status BlockCholesky::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
  if (!factorized_) return Status::Internal("block Cholesky: Solve before a successful Factorize");
  if (b.size() != kBlock * nodes_) return Status::InvalidInput("block Cholesky: the right-hand side has the wrong size");
  using Vector = Eigen::Matrix<double, kBlock, 1>;
  std::vector<Vector> y(nodes_);
  for (int j = 0; j < nodes_; ++j) y[j] = b.segment<kBlock>(kBlock * perm_[j]);
  for (int j = 0; j < nodes_; ++j) {  // L y = b
    diagonal_[j].triangularView<Eigen::Lower>().solveInPlace(y[j]);
    for (int s = 0; s < static_cast<int>(rows_[j].size()); ++s) y[rows_[j][s]].noalias() -= below_[j][s] * y[j];
  }
  for (int j = nodes_ - 1; j >= 0; --j) {  // Lᵀ x = y
    for (int s = 0; s < static_cast<int>(rows_[j].size()); ++s) y[j].noalias() -= below_[j][s].transpose() * y[rows_[j][s]];
    diagonal_[j].transpose().triangularView<Eigen::Upper>().solveInPlace(y[j]);
  }
  x->resize(b.size());
  for (int j = 0; j < nodes_; ++j) x->segment<kBlock>(kBlock * perm_[j]) = y[j];
  return Status::Ok();
}

}  // namespace pqlayout
