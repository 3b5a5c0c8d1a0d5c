#include "geometry/scalar_field_extrema.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace pqlayout {

std::vector<PersistentMinimum> PersistentMinima(const SurfaceModel& surface, const std::vector<double>& values,
                                                double min_persistence) {
  const int n = surface.num_vertices();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return values[a] < values[b] || (values[a] == values[b] && a < b); });
  std::vector<int> parent(n, -1);  // -1: not yet swept
  std::vector<int> birth(n, -1);   // per root: the vertex where its basin started
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<PersistentMinimum> minima;
  const TriMesh& mesh = surface.mesh();
  for (const int v : order) {
    parent[v] = v;
    birth[v] = v;
    for (const auto u : mesh.vv_range(VertexHandle(v))) {
      if (parent[u.idx()] < 0) continue;
      const int a = find(v), b = find(u.idx());
      if (a == b) continue;
      // The basin with the higher minimum dies here.
      const int older = values[birth[a]] <= values[birth[b]] ? a : b;
      const int younger = older == a ? b : a;
      const double persistence = values[v] - values[birth[younger]];
      if (birth[younger] != v && persistence > min_persistence && !surface.is_boundary(birth[younger]))
        minima.push_back({birth[younger], values[birth[younger]], persistence});
      parent[younger] = older;
    }
  }
  if (n > 0 && !surface.is_boundary(order[0]))
    minima.push_back({order[0], values[order[0]], std::numeric_limits<double>::infinity()});
  std::sort(minima.begin(), minima.end(), [](const auto& a, const auto& b) { return a.value < b.value; });
  return minima;
}

}  // namespace pqlayout
