// DropInteriorValence2Vertices, CentreSplit and QuadAndCentreSplit (quad_cleanup.h): the
// clean-up's vertex removals and additions, apart from quad_cleanup.cc to keep each file short.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "geometry/quad_cleanup.h"
#include "geometry/planarity.h"
#include "geometry/polygon_shape.h"

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

constexpr int kCentreGrid = 4;        // CentreSplit's search: (2·4 + 1)² places
constexpr double kCentreReach = 0.6;   // × the mean corner distance from the vertex average

// An interior 6- or 8-gon that no diagonals cut well (corners alternately sharp and flat, as
// around a −½ or −1 singularity of the guidance: the GC curvature layout, the canopy, the wavy
// roof) gets a vertex joined to every other corner: 3 or 4 quads around a new vertex of valence
// 3 or 4, if every quad angle is within [min_angle, 180° − min_angle]. The vertex goes at the
// corners' average, or if no quads are good enough there, at the place of a grid round it
// where the worst quad angle is best (kCentreGrid, kCentreReach); no spoke may be shorter than
// min_edge. It is marked `centre`: the extraction puts it on the surface (PlaceCentreVertices).
bool CentreSplit(const std::vector<int>& face, const std::set<std::pair<int, int>>& halfedges, double min_angle,
                 double min_edge, Polygons* m, std::vector<std::vector<int>>* faces) {
  const size_t n = face.size();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const int v : face) centroid += m->position[v] / static_cast<double>(n);
  const int c = static_cast<int>(m->position.size());
  m->position.push_back(centroid);
  QuadMeshVertex origin;
  origin.centre = true;
  m->origin.push_back(origin);
  double best_score = min_angle;
  std::vector<std::vector<int>> best;
  Eigen::Vector3d best_centre = centroid;
  const auto try_centre = [&](const Eigen::Vector3d& centre) {
    m->position[c] = centre;
    for (size_t parity = 0; parity < 2; ++parity) {
      std::vector<std::vector<int>> pieces;
      bool long_enough = true;  // no spoke shorter than min_edge
      for (size_t k = parity; k < n + parity; k += 2) {
        pieces.push_back({face[k % n], face[(k + 1) % n], face[(k + 2) % n], c});
        long_enough = long_enough && (m->position[face[k % n]] - centre).norm() >= min_edge;
      }
      if (!long_enough) continue;
      const double score = CutScore(*m, face, pieces, halfedges, nullptr);
      if (score >= best_score) best_score = score, best = std::move(pieces), best_centre = centre;
    }
  };
  try_centre(centroid);
  if (best.empty()) {
    // The vertex average can sit where some quad gets a sharp or flat corner (a cell with a
    // long side): search the polygon's plane round it, on a 9 × 9 grid spanning ±0.6 of the
    // mean corner distance, for the place whose worst quad angle is best.
    const Eigen::Vector3d normal = NewellNormal(m->position, face);
    if (normal.squaredNorm() > 0.0) {
      const Eigen::Vector3d u = normal.unitOrthogonal(), w = normal.cross(u);
      double radius = 0.0;
      for (const int v : face) radius += (m->position[v] - centroid).norm() / static_cast<double>(n);
      for (int i = -kCentreGrid; i <= kCentreGrid; ++i)
        for (int j = -kCentreGrid; j <= kCentreGrid; ++j)
          if (i != 0 || j != 0)
            try_centre(centroid + kCentreReach * radius * (double(i) / kCentreGrid * u + double(j) / kCentreGrid * w));
    }
  }
  if (best.empty()) {
    m->position.pop_back();
    m->origin.pop_back();
    return false;
  }
  m->position[c] = best_centre;
  faces->insert(faces->end(), best.begin(), best.end());
  return true;
}

// An interior 8-gon that neither diagonals nor a centre vertex cut well (two reflex corners
// side by side, next to an opening or a −½ singularity): a quad cut off by a diagonal, the
// hexagon left split round a centre vertex (CentreSplit) — 4 quads, the vertex of valence 3.
// The cut-off quads are tried best-shaped first.
bool QuadAndCentreSplit(const std::vector<int>& face, const std::set<std::pair<int, int>>& halfedges,
                        double min_angle, double min_edge, Polygons* m, std::vector<std::vector<int>>* faces) {
  std::vector<std::pair<double, size_t>> cuts;
  for (size_t k = 0; k < 8; ++k) {
    const std::vector<int> quad{face[k], face[(k + 1) % 8], face[(k + 2) % 8], face[(k + 3) % 8]};
    const double score = CutScore(*m, face, {quad}, halfedges, nullptr);
    if (score >= min_angle) cuts.push_back({score, k});
  }
  std::sort(cuts.rbegin(), cuts.rend());
  for (const auto& [score, k] : cuts) {
    std::vector<int> hexagon;
    for (size_t i = 3; i <= 8; ++i) hexagon.push_back(face[(k + i) % 8]);
    if (!CentreSplit(hexagon, halfedges, min_angle, min_edge, m, faces)) continue;
    faces->push_back({face[k], face[(k + 1) % 8], face[(k + 2) % 8], face[(k + 3) % 8]});
    return true;
  }
  return false;
}

}  // namespace pqlayout::extraction_internal
