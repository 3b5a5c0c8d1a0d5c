// BlockCholesky: see solver/block_cholesky.h.
#include "solver/block_cholesky.h"

#include <Eigen/Cholesky>
#include <Eigen/OrderingMethods>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <thread>

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
  Structure(std::vector<int>(order.indices().data(), order.indices().data() + nodes_));
  PlanSplit();
  diagonal_.assign(nodes_, Block::Zero());
  below_.assign(nodes_, {});
  for (int j = 0; j < nodes_; ++j) below_[j].assign(rows_[j].size(), Block::Zero());
}

void BlockCholesky::Structure(std::vector<int> perm) {
  perm_ = std::move(perm);
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
}

// The two threads' columns (block_cholesky.h). A column's cost is its block products (6 × 6 × 6
// each): one per row of L below each of its left-looking updates, one solve per block of its
// own. From the roots, the heaviest subtree in the set is replaced by its children (its root goes
// above) while that helps: at each step the set is dealt out heaviest first to the lighter
// thread, and the step with the least (above + larger share) is kept. Not split below
// kMinSplitCost products (the h = 1.5 m Great Court's frame, 2,668 nodes and 3.9e5 products, is) or where that
// would save less than a tenth.
void BlockCholesky::PlanSplit() {
  // ~8 ms of factor. Below it a second thread buys nothing: the Great Court's frame at h = 3 m
  // (756 nodes, 4.6e4 products) ran as fast either way, and at 1M triangles, beside the
  // background writer's files, its evaluations took 0.60-0.63 s on one thread, 0.65-0.73 s on two.
  constexpr double kMinSplitCost = 2e5;
  constexpr int kMaxSteps = 4096;
  columns_[0].clear(), columns_[1].clear();
  std::vector<double> own(nodes_, 1.0), subtree(nodes_, 0.0);
  std::vector<std::vector<int>> children(nodes_);
  std::vector<int> roots;
  for (int j = 0; j < nodes_; ++j) {
    own[j] += static_cast<double>(rows_[j].size());
    for (const auto& [k, p] : row_entries_[j]) own[j] += static_cast<double>(rows_[k].size() - p);
  }
  double total = 0.0;
  for (int j = 0; j < nodes_; ++j) {  // children before parents
    subtree[j] += own[j], total += own[j];
    if (rows_[j].empty()) roots.push_back(j);
    else subtree[rows_[j].front()] += subtree[j], children[rows_[j].front()].push_back(j);
  }
  if (total < kMinSplitCost) return;
  // Deals the subtrees of `set` out, heaviest first (ties by column), each to the thread with
  // the less work so far; `share` the two threads' work; each subtree's thread, if asked.
  const auto heavier = [&](int a, int b) { return subtree[a] != subtree[b] ? subtree[a] > subtree[b] : a < b; };
  double share[2];
  const auto deal = [&](std::vector<int>& set, std::vector<int>* root_thread) {
    std::sort(set.begin(), set.end(), heavier);
    share[0] = share[1] = 0.0;
    for (const int r : set) {
      const int t = share[1] < share[0] ? 1 : 0;
      share[t] += subtree[r];
      if (root_thread != nullptr) root_thread->push_back(t);
    }
  };
  std::vector<int> set = roots, taken;  // taken: the columns moved above, in order
  double above = 0.0, best = total;
  size_t best_taken = 0;
  for (int step = 0; step < kMaxSteps && !set.empty(); ++step) {
    deal(set, nullptr);
    if (above + std::max(share[0], share[1]) < best) best = above + std::max(share[0], share[1]), best_taken = taken.size();
    const int heaviest = set.front();
    set.erase(set.begin());
    set.insert(set.end(), children[heaviest].begin(), children[heaviest].end());
    taken.push_back(heaviest), above += own[heaviest];
  }
  if (best > 0.9 * total) return;
  // Replay to the best step: its set dealt out as above, each subtree to one thread.
  set = roots;
  for (size_t t = 0; t < best_taken; ++t) {
    set.erase(std::find(set.begin(), set.end(), taken[t]));
    set.insert(set.end(), children[taken[t]].begin(), children[taken[t]].end());
  }
  std::vector<int> root_thread, thread_of(nodes_, -1);
  deal(set, &root_thread);
  for (size_t i = 0; i < set.size(); ++i) {
    std::vector<int> stack{set[i]};
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      thread_of[c] = root_thread[i];
      stack.insert(stack.end(), children[c].begin(), children[c].end());
    }
  }
  // The columns above the subtrees (ascending: each after its descendants) to whichever thread
  // has the less work so far; a thread waits where it needs a column of the other's.
  for (int j = 0; j < nodes_; ++j) {
    int t = thread_of[j];
    if (t < 0) t = share[1] < share[0] ? 1 : 0, share[t] += own[j];
    columns_[t].push_back(j);
  }
}

struct BlockCholesky::Scratch {
  explicit Scratch(int nodes) : slot(nodes, -1) {}
  std::vector<int> slot;  // row node (new) → its place in the column being factored
  std::vector<Block> work;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;  // L's diagonal
  int failed = -1;
};

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
  Scratch first(nodes_), second(nodes_);
  bool ok = true;
  if (threads_ >= 2 && !columns_[1].empty()) {
    const std::unique_ptr<std::atomic<char>[]> done(new std::atomic<char>[nodes_]);
    for (int j = 0; j < nodes_; ++j) done[j].store(0, std::memory_order_relaxed);
    std::atomic<bool> stop{false};
    bool second_ok = true;
    std::thread worker([&] { second_ok = FactorColumns(A, columns_[1], &second, done.get(), &stop); });
    ok = FactorColumns(A, columns_[0], &first, done.get(), &stop);
    worker.join();
    ok = ok && second_ok;
  }
  if (threads_ < 2 || columns_[1].empty() || !ok) {  // one thread, or a failure: the one that one thread finds first
    first = Scratch(nodes_);
    std::vector<int> all(nodes_);
    for (int j = 0; j < nodes_; ++j) all[j] = j;
    ok = FactorColumns(A, all, &first);
  }
  if (!ok) {
    failed_row_ = kBlock * perm_[first.failed];
    return Status::Internal("block Cholesky: not positive definite at node block " + std::to_string(perm_[first.failed]));
  }
  const double lo = std::min(first.lo, second.lo), hi = std::max(first.hi, second.hi);
  rcond_ = nodes_ > 0 ? (lo / hi) * (lo / hi) : 0.0;
  factorized_ = true;
  return Status::Ok();
}

bool BlockCholesky::FactorColumns(const Eigen::SparseMatrix<double>& A, const std::vector<int>& columns, Scratch* s,
                                  std::atomic<char>* done, std::atomic<bool>* stop) {
  std::vector<int>& slot = s->slot;
  std::vector<Block>& work = s->work;
  Block work_diagonal;
  for (const int j : columns) {
    const std::vector<int>& rows = rows_[j];
    for (int r = 0; r < static_cast<int>(rows.size()); ++r) slot[rows[r]] = r;
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
      if (done != nullptr)  // column k may be the other thread's: wait until it is finished
        while (done[k].load(std::memory_order_acquire) == 0) {
          if (stop->load(std::memory_order_relaxed)) return false;
          std::this_thread::yield();
        }
      const Block ljk_t = below_[k][p].transpose();
      work_diagonal.noalias() -= below_[k][p] * ljk_t;
      for (int q = p + 1; q < static_cast<int>(rows_[k].size()); ++q)
        work[slot[rows_[k][q]]].noalias() -= below_[k][q] * ljk_t;
    }
    const Eigen::LLT<Block> llt(work_diagonal);
    if (llt.info() != Eigen::Success) {
      s->failed = j;
      if (stop != nullptr) stop->store(true, std::memory_order_relaxed);
      return false;
    }
    diagonal_[j] = llt.matrixL();
    for (int r = 0; r < static_cast<int>(rows.size()); ++r)
      below_[j][r] = diagonal_[j].triangularView<Eigen::Lower>().solve(work[r].transpose()).transpose();
    for (int d = 0; d < kBlock; ++d) s->lo = std::min(s->lo, diagonal_[j](d, d)), s->hi = std::max(s->hi, diagonal_[j](d, d));
    for (const int i : rows) slot[i] = -1;
    if (done != nullptr) done[j].store(1, std::memory_order_release);
  }
  return true;
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
