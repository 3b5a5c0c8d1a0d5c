#include "solver/supernodal_cholesky.h"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>

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
// front one buffer each, sized beforehand: at 479k unknowns a vector per supernode spent more
// time in page faults than in arithmetic.
Status SupernodalCholesky::FactorizeNumeric(const Lower& C) {
  const int supernodes = static_cast<int>(rows_.size());
  std::vector<std::vector<int>> kids(supernodes);
  for (int s = 0; s < supernodes; ++s)
    if (parent_[s] != -1) kids[parent_[s]].push_back(s);
  offset_.assign(supernodes + 1, 0);
  size_t largest_front = 0, stack_top = 0, stack_peak = 0;
  for (int s = 0; s < supernodes; ++s) {
    const size_t ns = first_[s + 1] - first_[s], r = rows_[s].size(), m = ns + r;
    offset_[s + 1] = offset_[s] + m * ns;
    largest_front = std::max(largest_front, m * m);
    for (const int c : kids[s]) stack_top -= rows_[c].size() * rows_[c].size();
    if (parent_[s] != -1) stack_top += r * r;
    stack_peak = std::max(stack_peak, stack_top);
  }
  factor_.Allocate(offset_[supernodes]);
  LargeArray front, stack;
  front.Allocate(largest_front);
  stack.Allocate(stack_peak);
  std::vector<int> local(n_, -1);
  stack_top = 0;
  for (int s = 0; s < supernodes; ++s) {
    const int f = first_[s], ns = first_[s + 1] - f;
    const std::vector<int>& below = rows_[s];
    const int m = ns + static_cast<int>(below.size());
    std::fill_n(front.data(), static_cast<size_t>(m) * m, 0.0);
    for (int j = 0; j < ns; ++j) local[f + j] = j;
    for (int a = 0; a < static_cast<int>(below.size()); ++a) local[below[a]] = ns + a;
    for (int j = 0; j < ns; ++j)  // A's entries, then the children's updates (extend-add), in a fixed order
      for (int e = C.outer[f + j]; e < C.outer[f + j + 1]; ++e)
        front.data()[static_cast<size_t>(j) * m + local[C.inner[e]]] += C.values[e];
    size_t children = 0;
    for (const int c : kids[s]) children += rows_[c].size() * rows_[c].size();
    const double* update = stack.data() + stack_top - children;
    for (const int c : kids[s]) {
      const std::vector<int>& rc = rows_[c];
      const int mc = static_cast<int>(rc.size());
      for (int b = 0; b < mc; ++b) {
        double* column = front.data() + static_cast<size_t>(local[rc[b]]) * m;
        const double* u = update + static_cast<size_t>(b) * mc;
        for (int a = b; a < mc; ++a) column[local[rc[a]]] += u[a];
      }
      update += static_cast<size_t>(mc) * mc;
    }
    stack_top -= children;
    const int failed = front_kernels::FactorFront(front.data(), m, ns);
    if (failed >= 0) {
      failed_row_ = perm_[f + failed];
      return Status::Internal("supernodal Cholesky: the matrix is not positive definite (row " +
                              std::to_string(failed_row_) + ")");
    }
    std::copy_n(front.data(), static_cast<size_t>(m) * ns, factor_.data() + offset_[s]);
    const int r = m - ns;
    if (parent_[s] != -1) {
      for (int b = 0; b < r; ++b)
        std::copy_n(front.data() + static_cast<size_t>(ns + b) * m + ns, r, stack.data() + stack_top + static_cast<size_t>(b) * r);
      stack_top += static_cast<size_t>(r) * r;
    }
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
