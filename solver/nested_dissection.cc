#include "solver/nested_dissection.h"

#include <algorithm>
#include <cassert>

namespace pqlayout {
namespace {

// Below this many rows a set is ordered as it stands (by row index): its dense block costs at
// most kLeafRows²/2 entries, and dissecting further buys nothing measurable.
constexpr int kLeafRows = 16;

class Dissection {
 public:
  Dissection(const Eigen::SparseMatrix<double>& A, const std::vector<Eigen::Vector3d>& points)
      : points_(points), owner_(A.rows(), -1) {
    // Symmetric adjacency (row → neighbours) from either triangle; a pair stored in both is
    // listed twice, which is harmless (the separator test asks only whether a neighbour is across).
    std::vector<int> degree(A.rows(), 0);
    for (int col = 0; col < A.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it)
        if (it.row() != it.col()) ++degree[it.row()], ++degree[it.col()];
    start_.assign(A.rows() + 1, 0);
    for (int v = 0; v < A.rows(); ++v) start_[v + 1] = start_[v] + degree[v];
    neighbours_.resize(start_.back());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int col = 0; col < A.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it)
        if (it.row() != it.col()) {
          neighbours_[fill[it.row()]++] = static_cast<int>(it.col());
          neighbours_[fill[it.col()]++] = static_cast<int>(it.row());
        }
    order_.reserve(A.rows());
  }

  std::vector<int> Run() {
    std::vector<int> all(owner_.size());
    for (size_t v = 0; v < all.size(); ++v) all[v] = static_cast<int>(v);
    Dissect(all.begin(), all.end());
    return std::move(order_);
  }

 private:
  using Iter = std::vector<int>::iterator;

  void Append(Iter first, Iter last) {
    std::sort(first, last);  // the same order whatever the standard library's nth_element left
    order_.insert(order_.end(), first, last);
  }

  // Orders the rows in [first, last): both halves first (recursively), their separator last.
  void Dissect(Iter first, Iter last) {
    const long n = last - first;
    if (n <= kLeafRows) return Append(first, last);
    Eigen::Vector3d lo = points_[*first], hi = lo;
    for (Iter it = first; it != last; ++it) lo = lo.cwiseMin(points_[*it]), hi = hi.cwiseMax(points_[*it]);
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const Iter middle = first + n / 2;
    std::nth_element(first, middle, last, [&](int a, int b) {
      const double pa = points_[a][axis], pb = points_[b][axis];
      return pa < pb || (pa == pb && a < b);
    });
    const int left = next_label_++, right = next_label_++;
    for (Iter it = first; it != middle; ++it) owner_[*it] = left;
    for (Iter it = middle; it != last; ++it) owner_[*it] = right;
    // The separator: the rows of one half next to the other, of whichever half has fewer;
    // moved to that half's end (the first half's) or start (the second's).
    const auto touches = [&](int v, int label) {
      for (int k = start_[v]; k < start_[v + 1]; ++k)
        if (owner_[neighbours_[k]] == label) return true;
      return false;
    };
    long in_first = 0, in_second = 0;
    for (Iter it = first; it != middle; ++it) in_first += touches(*it, right);
    for (Iter it = middle; it != last; ++it) in_second += touches(*it, left);
    // Ordered: both halves' interiors, then the separator (dissecting a range permutes only it).
    if (in_first <= in_second) {
      const Iter cut = std::stable_partition(first, middle, [&](int v) { return !touches(v, right); });
      Dissect(first, cut);
      Dissect(middle, last);
      Append(cut, middle);
    } else {
      const Iter cut = std::stable_partition(middle, last, [&](int v) { return touches(v, left); });
      Dissect(first, middle);
      Dissect(cut, last);
      Append(middle, cut);
    }
  }

  const std::vector<Eigen::Vector3d>& points_;
  std::vector<int> owner_;  // the label of the set a row was last assigned to
  std::vector<int> start_, neighbours_;
  std::vector<int> order_;
  int next_label_ = 0;
};

}  // namespace

std::vector<int> NestedDissectionOrdering(const Eigen::SparseMatrix<double>& A,
                                          const std::vector<Eigen::Vector3d>& points) {
  assert(A.rows() == A.cols() && points.size() == static_cast<size_t>(A.rows()));
  return Dissection(A, points).Run();
}

bool IsPermutation(const std::vector<int>& perm, long n) {
  if (static_cast<long>(perm.size()) != n) return false;
  std::vector<char> seen(n, 0);
  for (const int k : perm) {
    if (k < 0 || k >= n || seen[k]) return false;
    seen[k] = 1;
  }
  return true;
}

}  // namespace pqlayout
