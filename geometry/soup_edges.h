// The edges of a triangle soup, shared by its validation (mesh_validation.cc) and its repairs
// (soup_repair.cc). Every face must be a triangle of existing vertices.
#pragma once

#include <numeric>
#include <tuple>
#include <vector>

#include "geometry/mesh_io.h"

namespace pqlayout {

// One side of an undirected edge as seen from a face: the key (lo < hi), the face, and whether
// the face runs lo → hi.
struct EdgeUse {
  int lo, hi, face;
  bool forward;
  bool operator<(const EdgeUse& o) const { return std::tie(lo, hi, face) < std::tie(o.lo, o.hi, o.face); }
};

// Every face's three edge uses, sorted (a counting sort by lo, then each small bucket: a full
// sort of the 3 million uses of a 1M-triangle reference took a quarter of a second).
std::vector<EdgeUse> SortedEdgeUses(const PolygonSoup& soup);

// Calls visit(first, count) for each run of uses of one undirected edge.
template <typename Visit>
void ForEachEdge(const std::vector<EdgeUse>& uses, Visit visit) {
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
    visit(i, j - i);
    i = j;
  }
}

class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int Find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  // The smaller root becomes the root of both, so every set keeps its smallest element.
  void Union(int a, int b) {
    a = Find(a), b = Find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace pqlayout
