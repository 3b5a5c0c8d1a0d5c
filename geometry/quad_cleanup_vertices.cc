// DropInteriorValence2Vertices (quad_cleanup.h), apart from quad_cleanup.cc to keep each file
// short.
#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include "geometry/quad_cleanup.h"

namespace pqlayout::extraction_internal {

int DropInteriorValence2Vertices(Polygons* m) {
  int dropped = 0;
  for (bool again = true; again;) {
    again = false;
    std::vector<std::set<int>> neighbours(m->position.size());
    std::vector<std::vector<int>> faces_of(m->position.size());
    std::map<std::pair<int, int>, int> edge_faces;
    for (size_t f = 0; f < m->faces.size(); ++f) {
      const auto& face = m->faces[f];
      for (size_t k = 0; k < face.size(); ++k) {
        const int a = face[k], b = face[(k + 1) % face.size()];
        neighbours[a].insert(b);
        neighbours[b].insert(a);
        faces_of[a].push_back(static_cast<int>(f));
        ++edge_faces[{std::min(a, b), std::max(a, b)}];
      }
    }
    for (size_t v = 0; v < m->position.size(); ++v) {
      if (m->origin[v].on_boundary || neighbours[v].size() != 2 || faces_of[v].size() != 2) continue;
      const bool interior = std::all_of(neighbours[v].begin(), neighbours[v].end(), [&](int w) {
        return edge_faces[{std::min<int>(v, w), std::max<int>(v, w)}] == 2;
      });
      auto& f1 = m->faces[faces_of[v][0]];
      auto& f2 = m->faces[faces_of[v][1]];
      if (!interior || (f1.size() == 3 && f2.size() == 3)) continue;
      // v's two edges both lie between f1 and f2: without v they share the chord instead; a
      // triangle becomes that chord and goes.
      for (auto* face : {&f1, &f2}) face->erase(std::find(face->begin(), face->end(), static_cast<int>(v)));
      ++dropped;
      again = true;
      break;  // the adjacency is stale now
    }
    m->faces.erase(std::remove_if(m->faces.begin(), m->faces.end(), [](const auto& face) { return face.size() < 3; }),
                   m->faces.end());
  }
  return dropped;
}

}  // namespace pqlayout::extraction_internal
