#include "solver/supernodal_cholesky.h"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>
#include <thread>
#include <utility>

#include "solver/front_kernels.h"
#include "solver/nested_dissection.h"

namespace pqlayout {

LargeArray::~LargeArray() { std::free(data_); }

void LargeArray::Allocate(size_t size) {
  constexpr size_t kHugePage = size_t{2} << 20;
  std::free(data_);
  data_ = nullptr;
  size_ = size;
  if (size == 0) return;
  const size_t bytes = (size * sizeof(double) + kHugePage - 1) / kHugePage * kHugePage;
  data_ = static_cast<double*>(std::aligned_alloc(kHugePage, bytes));
  if (data_ == nullptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  ::madvise(data_, bytes, MADV_HUGEPAGE);  // a hint: where refused, ordinary pages
#endif
}

namespace {

// CHOLMOD's default relaxation (cholmod_common: nrelax, zrelax): a child supernode is merged
// into its parent if the result has at most 4 columns, or at most 16 with < 80 % explicit zeros,
// or at most 48 with < 10 %, or any number with < 5 %.
constexpr int kRelaxColumns[3] = {4, 16, 48};
constexpr double kRelaxZeros[3] = {0.8, 0.1, 0.05};

bool Relax(double columns, double rows, double nonzeros) {
  if (columns <= kRelaxColumns[0]) return true;
  const double stored = columns * rows - columns * (columns - 1.0) / 2.0;  // a trapezoid
  const double zeros = (stored - nonzeros) / stored;
  return (columns <= kRelaxColumns[1] && zeros < kRelaxZeros[0]) ||
         (columns <= kRelaxColumns[2] && zeros < kRelaxZeros[1]) || zeros < kRelaxZeros[2];
}

// The elimination tree of a pattern given by its upper triangle's columns (Liu 1986, with path
// compression): parent[j] = the first row below j in L's column j, or −1.
std::vector<int> EliminationTree(const std::vector<std::vector<int>>& upper) {
  const int n = static_cast<int>(upper.size());
  std::vector<int> parent(n, -1), ancestor(n, -1);
  for (int k = 0; k < n; ++k)
    for (int i : upper[k])
      while (i != -1 && i < k) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) parent[i] = k;
        i = next;
      }
  return parent;
}

// post[k] = the node visited k-th by a depth-first postorder of the forest (children in
// increasing order), so that every subtree is a contiguous range.
std::vector<int> Postorder(const std::vector<int>& parent) {
  const int n = static_cast<int>(parent.size());
  std::vector<int> head(n, -1), next(n, -1), post, stack;
  for (int j = n - 1; j >= 0; --j)
    if (parent[j] != -1) next[j] = head[parent[j]], head[parent[j]] = j;
  post.reserve(n);
  for (int root = 0; root < n; ++root) {
    if (parent[root] != -1) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const int j = stack.back();
      if (head[j] != -1) {
        const int child = head[j];
        head[j] = next[child];
        stack.push_back(child);
      } else {
        stack.pop_back();
        post.push_back(j);
      }
    }
  }
  return post;
}

}  // namespace

SupernodalCholesky::Lower SupernodalCholesky::Permuted(const Eigen::SparseMatrix<double>& A) const {
  Lower C;
  C.outer.assign(n_ + 1, 0);
  for (int j = 0; j < n_; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (inverse_[it.row()] >= inverse_[j]) ++C.outer[inverse_[j] + 1];
  for (int j = 0; j < n_; ++j) C.outer[j + 1] += C.outer[j];
  C.inner.resize(C.outer[n_]);
  C.values.resize(C.outer[n_]);
  std::vector<int> fill(C.outer.begin(), C.outer.end() - 1);
  for (int j = 0; j < n_; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (inverse_[it.row()] >= inverse_[j]) {
        const int at = fill[inverse_[j]]++;
        C.inner[at] = inverse_[it.row()];
        C.values[at] = it.value();
      }
  return C;
}

// Supernodes of the (already postordered) C and their row structures.
void SupernodalCholesky::Analyze(const Lower& C) {
  std::vector<std::vector<int>> upper(n_);  // L's row pattern sources: row k's entries left of k
  for (int j = 0; j < n_; ++j)
    for (int e = C.outer[j]; e < C.outer[j + 1]; ++e)
      if (C.inner[e] > j) upper[C.inner[e]].push_back(j);
  const std::vector<int> parent = EliminationTree(upper);
  std::vector<int> count(n_, 1), mark(n_, -1), children(n_, 0);  // count: L's column counts, diagonal included
  for (int k = 0; k < n_; ++k) {  // row k of L: the row subtree from upper[k]'s entries to k
    mark[k] = k;
    for (int i : upper[k])
      for (; mark[i] != k; i = parent[i]) mark[i] = k, ++count[i];
    if (parent[k] != -1) ++children[parent[k]];
  }
  // Fundamental supernodes (a chain of columns with nested structures), then relaxed
  // amalgamation from the root down: a supernode merged into the (merged) parent it precedes.
  std::vector<int> start;
  for (int j = 0; j < n_; ++j)
    if (j == 0 || parent[j - 1] != j || count[j - 1] != count[j] + 1 || children[j] != 1) start.push_back(j);
  const int fundamental = static_cast<int>(start.size());
  start.push_back(n_);
  std::vector<int> super_of(n_);
  for (int s = 0; s < fundamental; ++s)
    for (int j = start[s]; j < start[s + 1]; ++j) super_of[j] = s;
  std::vector<int> merged_into(fundamental, -1), first(start.begin(), start.end() - 1);
  std::vector<double> columns(fundamental), rows(fundamental), nonzeros(fundamental, 0.0);
  for (int s = 0; s < fundamental; ++s) {
    columns[s] = start[s + 1] - start[s];
    rows[s] = count[start[s]];
    for (int j = start[s]; j < start[s + 1]; ++j) nonzeros[s] += count[j];
  }
  const auto find = [&](int s) {
    while (merged_into[s] != -1) s = merged_into[s];
    return s;
  };
  for (int s = fundamental - 2; s >= 0; --s) {
    const int last = start[s + 1] - 1;
    if (parent[last] == -1) continue;
    const int p = find(super_of[parent[last]]);
    if (first[p] != last + 1 || !Relax(columns[s] + columns[p], columns[s] + rows[p], nonzeros[s] + nonzeros[p])) continue;
    merged_into[s] = p;
    first[p] = start[s];
    columns[p] += columns[s];
    rows[p] += columns[s];
    nonzeros[p] += nonzeros[s];
  }
  first_.clear();
  for (int s = 0; s < fundamental; ++s)
    if (merged_into[s] == -1) first_.push_back(first[s]);
  std::sort(first_.begin(), first_.end());
  const int supernodes = static_cast<int>(first_.size());
  first_.push_back(n_);
  for (int s = 0; s < supernodes; ++s)
    for (int j = first_[s]; j < first_[s + 1]; ++j) super_of[j] = s;
  parent_.assign(supernodes, -1);
  rows_.assign(supernodes, {});
  std::vector<std::vector<int>> kids(supernodes);
  for (int s = 0; s < supernodes; ++s) {
    const int last = first_[s + 1] - 1;
    if (parent[last] != -1) parent_[s] = super_of[parent[last]], kids[parent_[s]].push_back(s);
  }
  std::fill(mark.begin(), mark.end(), -1);
  for (int s = 0; s < supernodes; ++s) {  // rows below: A's columns' and the children's
    const int last = first_[s + 1] - 1;
    std::vector<int>& below = rows_[s];
    const auto add = [&](int i) {
      if (i > last && mark[i] != s) mark[i] = s, below.push_back(i);
    };
    for (int j = first_[s]; j <= last; ++j)
      for (int e = C.outer[j]; e < C.outer[j + 1]; ++e) add(C.inner[e]);
    for (const int c : kids[s])
      for (const int i : rows_[c]) add(i);
    std::sort(below.begin(), below.end());
  }
  flops_ = nonzeros_ = 0.0;
  for (int s = 0; s < supernodes; ++s) {
    const double ns = first_[s + 1] - first_[s], m = ns + rows_[s].size();
    nonzeros_ += ns * m - ns * (ns - 1.0) / 2.0;
    for (int j = 0; j < ns; ++j) flops_ += (m - j) * (m - j);
  }
}

Status SupernodalCholesky::Factorize(const Eigen::SparseMatrix<double>& A, const std::vector<int>& perm) {
  factorized_ = false;
  failed_row_ = -1;
  second_thread_supernodes_ = 0;
  if (A.rows() != A.cols() || A.rows() == 0 || !A.isCompressed())
    return Status::InvalidInput("supernodal Cholesky: the matrix is not square, empty or not compressed (" +
                                std::to_string(A.rows()) + " x " + std::to_string(A.cols()) + ")");
  n_ = static_cast<int>(A.rows());
  for (int k = 0; k < A.nonZeros(); ++k)
    if (!std::isfinite(A.valuePtr()[k])) {
      failed_row_ = A.innerIndexPtr()[k];
      return Status::InvalidInput("supernodal Cholesky: row " + std::to_string(failed_row_) + " has a non-finite entry");
    }
  if (!IsPermutation(perm, n_))
    return Status::InvalidInput("supernodal Cholesky: the ordering is not a permutation of the " + std::to_string(n_) + " rows");
  // The given order, refined by the postorder of its elimination tree (the same fill; every
  // subtree's columns contiguous, so that chains become supernodes).
  perm_ = perm;
  inverse_.assign(n_, 0);
  for (int k = 0; k < n_; ++k) inverse_[perm_[k]] = k;
  {
    std::vector<std::vector<int>> upper(n_);
    for (int j = 0; j < n_; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
        if (inverse_[it.row()] < inverse_[j]) upper[inverse_[j]].push_back(inverse_[it.row()]);
    const std::vector<int> post = Postorder(EliminationTree(upper));
    for (int k = 0; k < n_; ++k) perm_[k] = perm[post[k]];
    for (int k = 0; k < n_; ++k) inverse_[perm_[k]] = k;
  }
  const Lower C = Permuted(A);
  Analyze(C);
  return FactorizeNumeric(C);
}

// Supernodes in order (a postorder of their tree), each front assembled from A's columns and
// its children's update matrices, which lie on top of the update stack in the children's order
// (LIFO: each subtree leaves only its root's update behind). L is one array, the stack and the
// front one buffer each per thread, sized beforehand: at 479k unknowns a vector per supernode
// spent more time in page faults than in arithmetic.
//
// Two threads where the machine has them: below the root's chain, the first supernode with two
// or more children (with a nested-dissection order, the top separator) has independent subtrees,
// split into two runs of consecutive subtrees with about the same flops, each factored on its own
// thread with its own buffers; then the rest. Every front is assembled and factored by the same
// code in the same order of sums whichever thread runs it (its children's updates added in the
// children's order, wherever they lie), so L is the same to the bit on any number of threads.
struct SupernodalCholesky::Workspace {
  LargeArray front, stack;
  std::vector<int> local;  // a row's position in the current front
  size_t top = 0;
  int failed_supernode = -1, failed_column = -1;
};

namespace {

// A run of supernodes [begin, end) in postorder.
using SupernodeRun = std::pair<int, int>;

// The two threads' runs (empty if there is no split; see above). kids: each supernode's children
// in order; flops: each supernode's own.
std::pair<SupernodeRun, SupernodeRun> SplitForTwoThreads(const std::vector<std::vector<int>>& kids,
                                                           const std::vector<double>& flops) {
  const int supernodes = static_cast<int>(kids.size());
  if (supernodes == 0) return {};
  std::vector<int> first_descendant(supernodes);
  std::vector<double> subtree(supernodes);
  for (int s = 0; s < supernodes; ++s) {  // postorder: every child before its parent
    first_descendant[s] = kids[s].empty() ? s : first_descendant[kids[s].front()];
    subtree[s] = flops[s];
    for (const int c : kids[s]) subtree[s] += subtree[c];
  }
  int split = supernodes - 1;  // the last root
  while (kids[split].size() == 1) split = kids[split].front();
  const std::vector<int>& k = kids[split];
  if (k.size() < 2) return {};
  double total = 0.0, left = 0.0, best = -1.0;
  for (const int c : k) total += subtree[c];
  size_t cut = 1;
  for (size_t t = 1; t < k.size(); ++t) {
    left += subtree[k[t - 1]];
    const double smaller = std::min(left, total - left);
    if (smaller > best) best = smaller, cut = t;
  }
  return {{first_descendant[k.front()], k[cut - 1] + 1}, {first_descendant[k[cut]], k.back() + 1}};
}

}  // namespace

// Factors the supernodes of `nodes` in order with the buffers of w; update[c] is where child c's
// update matrix lies (in any workspace's stack). Stops at the first supernode that is not
// positive definite (w->failed_supernode).
void SupernodalCholesky::FactorSupernodes(const Lower& C, const std::vector<std::vector<int>>& kids,
                                          const std::vector<int>& nodes, std::vector<const double*>* update,
                                          Workspace* w) {
  if (nodes.empty()) return;
  size_t largest_front = 0, top = 0, peak = 0;
  std::vector<char> here(rows_.size(), 0);
  for (const int s : nodes) here[s] = 1;
  for (const int s : nodes) {
    const size_t ns = first_[s + 1] - first_[s], r = rows_[s].size(), m = ns + r;
    largest_front = std::max(largest_front, m * m);
    for (const int c : kids[s])
      if (here[c]) top -= rows_[c].size() * rows_[c].size();
    if (parent_[s] != -1) top += r * r;
    peak = std::max(peak, top);
  }
  w->front.Allocate(largest_front);
  w->stack.Allocate(peak);
  w->local.assign(n_, -1);
  w->top = 0;
  double* front = w->front.data();
  for (const int s : nodes) {
    const int f = first_[s], ns = first_[s + 1] - f;
    const std::vector<int>& below = rows_[s];
    const int m = ns + static_cast<int>(below.size());
    std::fill_n(front, static_cast<size_t>(m) * m, 0.0);
    for (int j = 0; j < ns; ++j) w->local[f + j] = j;
    for (int a = 0; a < static_cast<int>(below.size()); ++a) w->local[below[a]] = ns + a;
    for (int j = 0; j < ns; ++j)  // A's entries, then the children's updates (extend-add), in a fixed order
      for (int e = C.outer[f + j]; e < C.outer[f + j + 1]; ++e)
        front[static_cast<size_t>(j) * m + w->local[C.inner[e]]] += C.values[e];
    for (const int c : kids[s]) {
      const std::vector<int>& rc = rows_[c];
      const int mc = static_cast<int>(rc.size());
      for (int b = 0; b < mc; ++b) {
        double* column = front + static_cast<size_t>(w->local[rc[b]]) * m;
        const double* u = (*update)[c] + static_cast<size_t>(b) * mc;
        for (int a = b; a < mc; ++a) column[w->local[rc[a]]] += u[a];
      }
      if (here[c]) w->top -= static_cast<size_t>(mc) * mc;  // LIFO: its children's were on top
    }
    const int failed = front_kernels::FactorFront(front, m, ns);
    if (failed >= 0) {
      w->failed_supernode = s;
      w->failed_column = f + failed;
      return;
    }
    std::copy_n(front, static_cast<size_t>(m) * ns, factor_.data() + offset_[s]);
    const int r = m - ns;
    if (parent_[s] != -1) {
      double* out = w->stack.data() + w->top;
      for (int b = 0; b < r; ++b) std::copy_n(front + static_cast<size_t>(ns + b) * m + ns, r, out + static_cast<size_t>(b) * r);
      (*update)[s] = out;
      w->top += static_cast<size_t>(r) * r;
    }
  }
}

Status SupernodalCholesky::FactorizeNumeric(const Lower& C) {
  const int supernodes = static_cast<int>(rows_.size());
  std::vector<std::vector<int>> kids(supernodes);
  for (int s = 0; s < supernodes; ++s)
    if (parent_[s] != -1) kids[parent_[s]].push_back(s);
  offset_.assign(supernodes + 1, 0);
  std::vector<double> flops(supernodes);
  for (int s = 0; s < supernodes; ++s) {
    const size_t ns = first_[s + 1] - first_[s], m = ns + rows_[s].size();
    offset_[s + 1] = offset_[s] + m * ns;
    flops[s] = static_cast<double>(m) * m * ns;
  }
  factor_.Allocate(offset_[supernodes]);
  std::vector<const double*> update(supernodes, nullptr);
  const auto [a, b] = threads_ > 1 ? SplitForTwoThreads(kids, flops) : std::pair<SupernodeRun, SupernodeRun>{};
  std::vector<int> nodes_a, nodes_b, before, after;  // before: other trees; after: the split and its ancestors
  for (int s = 0; s < supernodes; ++s) {
    if (s >= a.first && s < a.second) nodes_a.push_back(s);
    else if (s >= b.first && s < b.second) nodes_b.push_back(s);
    else (s < a.first || a.first == a.second ? before : after).push_back(s);
  }
  // Each run its own buffers, kept until the end: a run's stack holds the updates that the
  // next run's supernodes read (the split's children's, for `after`).
  Workspace w_before, w_a, w_b, w_after;
  FactorSupernodes(C, kids, before, &update, &w_before);
  if (w_before.failed_supernode < 0) {
    std::thread worker;
    if (!nodes_b.empty()) worker = std::thread([&] { FactorSupernodes(C, kids, nodes_b, &update, &w_b); });
    second_thread_supernodes_ = static_cast<int>(nodes_b.size());
    FactorSupernodes(C, kids, nodes_a, &update, &w_a);
    if (worker.joinable()) worker.join();
    if (w_a.failed_supernode < 0 && w_b.failed_supernode < 0) FactorSupernodes(C, kids, after, &update, &w_after);
  }
  for (const Workspace* w : {&w_before, &w_a, &w_b, &w_after}) {  // the first in postorder, as one thread would find it
    if (w->failed_supernode < 0) continue;
    failed_row_ = perm_[w->failed_column];
    return Status::Internal("supernodal Cholesky: the matrix is not positive definite (row " + std::to_string(failed_row_) +
                            ")");
  }
  factorized_ = true;
  return Status::Ok();
}

Status SupernodalCholesky::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
  if (!factorized_) return Status::Internal("supernodal Cholesky: Solve before a successful Factorize");
  if (b.size() != n_) return Status::InvalidInput("supernodal Cholesky: the right-hand side has the wrong size");
  std::vector<double> y(n_);
  for (int k = 0; k < n_; ++k) y[k] = b[perm_[k]];
  const int supernodes = static_cast<int>(rows_.size());
  for (int s = 0; s < supernodes; ++s) {  // L y = b
    const int f = first_[s], ns = first_[s + 1] - f, m = ns + static_cast<int>(rows_[s].size());
    const double* L = factor_.data() + offset_[s];
    for (int j = 0; j < ns; ++j) {
      const double* column = L + static_cast<size_t>(j) * m;
      const double yj = y[f + j] /= column[j];
      for (int i = j + 1; i < ns; ++i) y[f + i] -= column[i] * yj;
      for (int a = 0; a < m - ns; ++a) y[rows_[s][a]] -= column[ns + a] * yj;
    }
  }
  for (int s = supernodes - 1; s >= 0; --s) {  // Lᵀ x = y
    const int f = first_[s], ns = first_[s + 1] - f, m = ns + static_cast<int>(rows_[s].size());
    const double* L = factor_.data() + offset_[s];
    for (int j = ns - 1; j >= 0; --j) {
      const double* column = L + static_cast<size_t>(j) * m;
      double t = y[f + j];
      for (int i = j + 1; i < ns; ++i) t -= column[i] * y[f + i];
      for (int a = 0; a < m - ns; ++a) t -= column[ns + a] * y[rows_[s][a]];
      y[f + j] = t / column[j];
    }
  }
  x->resize(n_);
  for (int k = 0; k < n_; ++k) (*x)[perm_[k]] = y[k];
  return Status::Ok();
}

}  // namespace pqlayout
