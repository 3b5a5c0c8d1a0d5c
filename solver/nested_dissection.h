// A fill-reducing ordering for sparse Cholesky factors of mesh matrices: nested dissection
// (George 1973, "Nested dissection of a regular finite element mesh") with its separators found
// by recursive coordinate bisection, the simplest geometric partitioner (Simon 1991).
//
// Why our own and not CHOLMOD's: the membrane's matrix on a 1M-triangle reference (479k
// unknowns) factored after CHOLMOD's AMD costs 1.06e10 flops (simplicial factor ~6 s); after
// METIS 3.9e9 flops (2.2 s), but METIS's ordering itself takes ~3 s there. The rows of a
// mesh matrix have points, and bisecting them by the median of the widest coordinate finds
// separators as short as METIS's on a surface in a fraction of the time
// (benchmarks/RESULTS.md, "The membrane's ordering").
//
// The set of rows is split at the median along the axis of its widest extent (ties by row
// index, so the split is the same on every machine and standard library); the rows of the
// first half with a neighbour in the second form the separator, ordered after both halves,
// which are dissected in turn down to kLeafRows rows. Each level costs O(n + nnz).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace pqlayout {

// perm[k] = the row of A eliminated k-th (CHOLMOD's UserPerm). A: n × n with a symmetric
// pattern (both triangles or either; only the pattern is read); points: one per row.
std::vector<int> NestedDissectionOrdering(const Eigen::SparseMatrix<double>& A,
                                          const std::vector<Eigen::Vector3d>& points);

// Whether perm holds each of 0 … n − 1 exactly once (an ordering a factor may be given).
bool IsPermutation(const std::vector<int>& perm, long n);

}  // namespace pqlayout
