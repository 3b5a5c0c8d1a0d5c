#include "geometry/soup_edges.h"

#include <algorithm>

namespace pqlayout {

std::vector<EdgeUse> SortedEdgeUses(const PolygonSoup& soup) {
  std::vector<int> start(soup.points.size() + 1, 0);
  for (const auto& face : soup.faces)
    for (int k = 0; k < 3; ++k) ++start[std::min(face[k], face[(k + 1) % 3]) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<EdgeUse> uses(3 * soup.faces.size());
  std::vector<int> next(start.begin(), start.end() - 1);
  for (size_t f = 0; f < soup.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = soup.faces[f][k], b = soup.faces[f][(k + 1) % 3];
      uses[next[std::min(a, b)]++] = {std::min(a, b), std::max(a, b), static_cast<int>(f), a < b};
    }
  for (size_t v = 0; v + 1 < start.size(); ++v)
    if (start[v + 1] - start[v] > 1) std::sort(uses.begin() + start[v], uses.begin() + start[v + 1]);
  return uses;
}

}  // namespace pqlayout
