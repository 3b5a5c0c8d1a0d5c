#include "geometry/quad_cleanup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "geometry/planarity.h"
#include "geometry/polygon_shape.h"

namespace pqlayout::extraction_internal {
namespace {

// ---- Short edges ---------------------------------------------------------------------------

bool CyclicallyAdjacent(const std::vector<int>& face, int u, int v) {
  const size_t n = face.size();
  for (size_t k = 0; k < n; ++k) {
    const int a = face[k], b = face[(k + 1) % n];
    if ((a == u && b == v) || (a == v && b == u)) return true;
  }
  return false;
}

// Every way to cut a polygon with an even number of sides into quads by non-crossing
// diagonals (each diagonal leaves an even number of sides on both sides).
void Quadrangulations(const std::vector<int>& polygon, std::vector<std::vector<std::vector<int>>>* out) {
  const size_t n = polygon.size();
  if (n == 4) {
    out->push_back({polygon});
    return;
  }
  // The quad containing edge (0, 1) is (0, 1, i, j), i even, j − i odd; the rest are the
  // polygons (1 … i), (i … j) and (j … n − 1, 0), each an edge or even-sided.
  for (size_t i = 2; i < n; i += 2)
    for (size_t j = i + 1; j < n; j += 2) {
      const std::vector<int> quad{polygon[0], polygon[1], polygon[i], polygon[j]};
      std::vector<std::vector<std::vector<int>>> left{{}}, right{{}};
      if (i > 2) {
        left.clear();
        Quadrangulations(std::vector<int>(polygon.begin() + 1, polygon.begin() + i + 1), &left);
      }
      if (j > i + 1) {
        right.clear();
        Quadrangulations(std::vector<int>(polygon.begin() + i, polygon.begin() + j + 1), &right);
      }
      std::vector<int> rest{polygon[0]};
      for (size_t k = j; k < n; ++k) rest.push_back(polygon[k]);
      std::vector<std::vector<std::vector<int>>> tail{{}};
      if (rest.size() > 2) {
        tail.clear();
        Quadrangulations(rest, &tail);
      }
      for (const auto& l : left)
        for (const auto& r : right)
          for (const auto& t : tail) {
            std::vector<std::vector<int>> quads{quad};
            quads.insert(quads.end(), l.begin(), l.end());
            quads.insert(quads.end(), r.begin(), r.end());
            quads.insert(quads.end(), t.begin(), t.end());
            out->push_back(std::move(quads));
          }
    }
}


// The adjacency CollapseRound and CollapseBlocker read.
struct Adjacency {
  std::vector<std::vector<int>> faces_of;
  std::vector<std::set<int>> neighbours;
  std::map<std::pair<int, int>, int> edge_faces;  // (min, max) → faces on the edge
  std::vector<char> topological_boundary;
  explicit Adjacency(const Polygons& m) : faces_of(m.position.size()), neighbours(m.position.size()),
                                          topological_boundary(m.position.size(), 0) {
    for (size_t f = 0; f < m.faces.size(); ++f) {
      const auto& face = m.faces[f];
      for (size_t k = 0; k < face.size(); ++k) {
        const int a = face[k], b = face[(k + 1) % face.size()];
        faces_of[a].push_back(int(f));
        neighbours[a].insert(b);
        neighbours[b].insert(a);
        ++edge_faces[{std::min(a, b), std::max(a, b)}];
      }
    }
    for (const auto& [e, count] : edge_faces)
      if (count == 1) topological_boundary[e.first] = topological_boundary[e.second] = 1;
  }
};

int Rank(const Polygons& m, int v) { return m.origin[v].corner ? 2 : (m.origin[v].on_boundary ? 1 : 0); }

const char* Blocker(const Polygons& m, const Adjacency& adj, int u, int v) {
  const std::pair<int, int> e{std::min(u, v), std::max(u, v)};
  const auto found = adj.edge_faces.find(e);
  if (found == adj.edge_faces.end()) return "not an edge";
  if (Rank(m, u) == 2 && Rank(m, v) == 2) return "both ends are boundary corners";
  const bool boundary_edge = found->second == 1;
  if (adj.topological_boundary[u] && adj.topological_boundary[v] && !boundary_edge)
    return "both ends are on the mesh boundary but the edge is not (it would pinch the mesh)";
  if (Rank(m, u) >= 1 && Rank(m, v) >= 1 && !boundary_edge)
    return "both ends are on the reference boundary but the edge crosses the surface (a chord)";
  // Link condition: common neighbours only through triangles on the edge.
  std::set<int> allowed;
  for (const int f : adj.faces_of[u]) {
    const auto& face = m.faces[f];
    if (std::find(face.begin(), face.end(), v) == face.end()) continue;
    if (!CyclicallyAdjacent(face, u, v)) return "its ends also meet across a face";
    if (face.size() == 3)
      for (const int w : face)
        if (w != u && w != v) allowed.insert(w);
  }
  for (const int w : adj.neighbours[u])
    if (w != v && adj.neighbours[v].count(w) && !allowed.count(w))
      return "its ends share a neighbour (the collapse would make the mesh non-manifold)";
  return nullptr;
}

}  // namespace

double CutScore(const Polygons& m, const std::vector<int>& face, const std::vector<std::vector<int>>& pieces,
                const std::set<std::pair<int, int>>& halfedges, const std::vector<char>* on_boundary) {
  double score = M_PI;
  for (const auto& piece : pieces) {
    score = std::min(score, ShapeAngle(m.position, piece));
    for (size_t k = 0; k < piece.size(); ++k) {
      const int a = piece[k], b = piece[(k + 1) % piece.size()];
      if (CyclicallyAdjacent(face, a, b)) continue;
      if (halfedges.count({a, b}) || halfedges.count({b, a})) return -1.0;
      if (on_boundary != nullptr && (*on_boundary)[a] && (*on_boundary)[b]) return -1.0;
    }
  }
  return score;
}

const char* CollapseBlocker(const Polygons& m, int u, int v) { return Blocker(m, Adjacency(m), u, v); }

// One round of collapses of edges shorter than min_length, on disjoint neighbourhoods.
int CollapseRound(double min_length, Polygons* m) {
  const Adjacency adj(*m);
  std::vector<std::pair<double, std::pair<int, int>>> short_edges;
  for (const auto& [e, count] : adj.edge_faces) {
    const double length = (m->position[e.first] - m->position[e.second]).norm();
    if (length < min_length) short_edges.push_back({length, e});
  }
  std::sort(short_edges.begin(), short_edges.end());
  std::vector<char> touched(m->faces.size(), 0);
  std::vector<int> target(m->position.size());
  std::iota(target.begin(), target.end(), 0);
  int collapsed = 0;
  for (const auto& [length, e] : short_edges) {
    auto [u, v] = e;
    bool free = true;
    for (const int f : adj.faces_of[u]) free &= !touched[f];
    for (const int f : adj.faces_of[v]) free &= !touched[f];
    if (!free || Blocker(*m, adj, u, v)) continue;
    if (Rank(*m, v) > Rank(*m, u)) std::swap(u, v);  // keep u
    target[v] = u;
    for (const int f : adj.faces_of[u]) touched[f] = 1;
    for (const int f : adj.faces_of[v]) touched[f] = 1;
    ++collapsed;
  }
  if (collapsed == 0) return 0;
  std::vector<std::vector<int>> faces;
  for (const auto& face : m->faces) {
    std::vector<int> mapped;
    for (const int v : face) {
      const int w = target[v];
      if (mapped.empty() || mapped.back() != w) mapped.push_back(w);
    }
    while (mapped.size() > 1 && mapped.back() == mapped.front()) mapped.pop_back();
    if (mapped.size() >= 3) faces.push_back(std::move(mapped));
  }
  m->faces = std::move(faces);
  return collapsed;
}

// Drops vertices no face uses.
void Compact(Polygons* m) {
  std::vector<int> index(m->position.size(), -1);
  Polygons compact;
  for (auto& face : m->faces)
    for (int& v : face) {
      if (index[v] < 0) {
        index[v] = static_cast<int>(compact.position.size());
        compact.position.push_back(m->position[v]);
        compact.origin.push_back(m->origin[v]);
      }
      v = index[v];
    }
  compact.faces = std::move(m->faces);
  *m = std::move(compact);
}

int DropFloatingParts(Polygons* m) {
  std::vector<int> parent(m->position.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& face : m->faces)
    for (const int v : face) parent[find(v)] = find(face[0]);
  std::vector<char> held(m->position.size(), 0);
  for (size_t v = 0; v < m->position.size(); ++v)
    if (m->origin[v].on_boundary) held[find(static_cast<int>(v))] = 1;
  const size_t before = m->faces.size();
  m->faces.erase(std::remove_if(m->faces.begin(), m->faces.end(), [&](const auto& face) { return !held[find(face[0])]; }),
                 m->faces.end());
  return static_cast<int>(before - m->faces.size());
}

// Boundary vertices that no interior edge reaches (valence 2, one face), are no corner and
// lie on a straight piece of the boundary (a curve that touched the boundary and left it
// again, or the end of a merged sliver) carry nothing: removed from their face.
int DropIdleBoundaryVertices(Polygons* m) {
  std::vector<std::set<int>> neighbours(m->position.size());
  std::vector<int> face_count(m->position.size(), 0);
  for (const auto& face : m->faces)
    for (size_t k = 0; k < face.size(); ++k) {
      neighbours[face[k]].insert(face[(k + 1) % face.size()]);
      neighbours[face[(k + 1) % face.size()]].insert(face[k]);
      ++face_count[face[k]];
    }
  int dropped = 0;
  for (auto& face : m->faces) {
    for (size_t k = 0; k < face.size() && face.size() > 3;) {
      const int v = face[k], prev = face[(k + face.size() - 1) % face.size()], next = face[(k + 1) % face.size()];
      const QuadMeshVertex& o = m->origin[v];
      const Eigen::Vector3d chord = m->position[next] - m->position[prev];
      const double off_chord = chord.norm() > 0.0
                                   ? (m->position[v] - m->position[prev]).cross(chord).norm() / chord.norm()
                                   : INFINITY;
      if (neighbours[v].size() == 2 && face_count[v] == 1 && o.on_boundary && !o.corner &&
          off_chord <= 1e-6 * chord.norm()) {
        face.erase(face.begin() + k);
        ++dropped;
      } else {
        ++k;
      }
    }
  }
  return dropped;
}

// Along a boundary crossed obliquely by both families the boundary cells alternate between
// triangles and pentagons. A triangle and a pentagon sharing a curve segment that ends on the
// boundary form a hexagon, which is re-split into two quads by the diagonal that gives the
// best-shaped quads (every angle between 20° and 160° in the hexagon's plane): the last segment of that curve then
// ends at the neighbouring boundary point. Returns the number of re-split pairs.

int ResplitBoundaryTrianglePentagonPairs(Polygons* m) {
  std::map<std::pair<int, int>, int> face_of_halfedge;
  for (size_t f = 0; f < m->faces.size(); ++f) {
    const auto& face = m->faces[f];
    for (size_t k = 0; k < face.size(); ++k) face_of_halfedge[{face[k], face[(k + 1) % face.size()]}] = int(f);
  }
  const auto has_edge = [&](int a, int b) { return face_of_halfedge.count({a, b}) || face_of_halfedge.count({b, a}); };
  struct Candidate {
    double score;
    int f1, f2;
    std::vector<int> q1, q2;
  };
  std::vector<Candidate> candidates;
  for (const auto& [halfedge, f1] : face_of_halfedge) {
    const auto [a, b] = halfedge;
    const auto twin = face_of_halfedge.find({b, a});
    if (twin == face_of_halfedge.end()) continue;
    const int f2 = twin->second;
    const size_t n1 = m->faces[f1].size(), n2 = m->faces[f2].size();
    if (!((n1 == 3 && n2 == 5) || (n1 == 5 && n2 == 3))) continue;
    if (m->origin[a].on_boundary == m->origin[b].on_boundary) continue;  // a curve's last segment only
    // The hexagon: f1 from b round to a, then f2 from a round to b (without repeating a, b).
    std::vector<int> hexagon;
    const auto& face1 = m->faces[f1];
    const auto& face2 = m->faces[f2];
    const size_t start1 = std::find(face1.begin(), face1.end(), b) - face1.begin();
    for (size_t k = 0; k < n1; ++k) hexagon.push_back(face1[(start1 + k) % n1]);
    const size_t start2 = std::find(face2.begin(), face2.end(), a) - face2.begin();
    for (size_t k = 1; k + 1 < n2; ++k) hexagon.push_back(face2[(start2 + k) % n2]);
    if (hexagon.size() != 6 || std::set<int>(hexagon.begin(), hexagon.end()).size() != 6) continue;
    const Eigen::Vector3d normal = NewellNormal(m->position, hexagon);
    if (!(normal.norm() > 0.0)) continue;
    const auto min_angle = [&](const std::vector<int>& quad) { return ShapeAngle(m->position, quad, normal); };
    for (int s = 0; s < 3; ++s) {
      const int p = hexagon[s], q = hexagon[s + 3];
      if (has_edge(p, q) || (m->origin[p].on_boundary && m->origin[q].on_boundary)) continue;
      std::vector<int> q1{hexagon[s], hexagon[s + 1], hexagon[s + 2], hexagon[s + 3]};
      std::vector<int> q2{hexagon[s + 3], hexagon[(s + 4) % 6], hexagon[(s + 5) % 6], hexagon[s]};
      const double score = std::min(min_angle(q1), min_angle(q2));
      if (score > kMinResplitAngle) candidates.push_back({score, f1, f2, q1, q2});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
  std::vector<char> used(m->faces.size(), 0);
  int resplit = 0;
  for (const Candidate& c : candidates) {
    if (used[c.f1] || used[c.f2]) continue;
    used[c.f1] = used[c.f2] = 1;
    m->faces[c.f1] = c.q1;
    m->faces[c.f2] = c.q2;
    ++resplit;
  }
  return resplit;
}

// Where two curves cross just inside the boundary, the corner they cut off is a boundary
// triangle (A, B on the boundary, X the crossing) between two boundary cells of five or more
// sides. Moving the crossing onto the boundary (X and B merged into A, or X and A into B,
// whichever gives the better-shaped faces, every quad angle within [min_angle, 180° −
// min_angle]) removes the triangle and makes both neighbours one side shorter: a triangle and
// two pentagons become two quads. Boundary corners are never merged away.
int CollapseBoundaryTriangles(double min_angle, Polygons* m) {
  std::map<std::pair<int, int>, int> face_of_halfedge;
  std::vector<std::vector<int>> faces_of(m->position.size());
  for (size_t f = 0; f < m->faces.size(); ++f) {
    const auto& face = m->faces[f];
    for (size_t k = 0; k < face.size(); ++k) {
      face_of_halfedge[{face[k], face[(k + 1) % face.size()]}] = int(f);
      faces_of[face[k]].push_back(int(f));
    }
  }
  std::vector<char> on_boundary(m->position.size(), 0);
  for (const auto& [halfedge, f] : face_of_halfedge)
    if (!face_of_halfedge.count({halfedge.second, halfedge.first})) on_boundary[halfedge.first] = on_boundary[halfedge.second] = 1;
  struct Candidate {
    double score;
    int triangle;
    std::vector<int> affected;
    std::vector<std::vector<int>> replaced;
  };
  std::vector<Candidate> candidates;
  for (size_t t = 0; t < m->faces.size(); ++t) {
    const auto& tri = m->faces[t];
    if (tri.size() != 3) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3], x = tri[(k + 2) % 3];
      if (face_of_halfedge.count({b, a}) || on_boundary[x]) continue;  // A–B on the boundary, X inside
      const auto across_a = face_of_halfedge.find({a, x}), across_b = face_of_halfedge.find({x, b});
      if (across_a == face_of_halfedge.end() || across_b == face_of_halfedge.end()) continue;
      if (m->faces[across_a->second].size() < 5 || m->faces[across_b->second].size() < 5) continue;
      std::vector<int> affected;
      for (const int v : {a, b, x})
        for (const int f : faces_of[v])
          if (f != int(t) && std::find(affected.begin(), affected.end(), f) == affected.end()) affected.push_back(f);
      for (const auto [keep, drop] : {std::pair<int, int>{a, b}, std::pair<int, int>{b, a}}) {
        if (m->origin[drop].corner) continue;
        Candidate c{M_PI, int(t), affected, {}};
        std::set<std::pair<int, int>> halfedges;
        bool valid = true;
        for (const int f : affected) {
          std::vector<int> mapped;
          for (const int v : m->faces[f]) {
            const int w = (v == x || v == drop) ? keep : v;
            if (mapped.empty() || mapped.back() != w) mapped.push_back(w);
          }
          while (mapped.size() > 1 && mapped.back() == mapped.front()) mapped.pop_back();
          valid &= mapped.size() >= 3 && std::set<int>(mapped.begin(), mapped.end()).size() == mapped.size();
          for (size_t i = 0; valid && i < mapped.size(); ++i) {
            const std::pair<int, int> h{mapped[i], mapped[(i + 1) % mapped.size()]};
            const auto existing = face_of_halfedge.find(h);
            valid &= halfedges.insert(h).second &&
                     (existing == face_of_halfedge.end() ||
                      std::find(affected.begin(), affected.end(), existing->second) != affected.end());
          }
          if (valid && mapped.size() <= 4) c.score = std::min(c.score, ShapeAngle(m->position, mapped));
          c.replaced.push_back(std::move(mapped));
        }
        if (valid && c.score >= min_angle) candidates.push_back(std::move(c));
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
  std::vector<char> used(m->faces.size(), 0), removed(m->faces.size(), 0);
  int collapsed = 0;
  for (const Candidate& c : candidates) {
    bool free = !used[c.triangle];
    for (const int f : c.affected) free &= !used[f];
    if (!free) continue;
    used[c.triangle] = removed[c.triangle] = 1;
    for (size_t i = 0; i < c.affected.size(); ++i) {
      used[c.affected[i]] = 1;
      m->faces[c.affected[i]] = c.replaced[i];
    }
    ++collapsed;
  }
  std::vector<std::vector<int>> faces;
  for (size_t f = 0; f < m->faces.size(); ++f)
    if (!removed[f]) faces.push_back(std::move(m->faces[f]));
  m->faces = std::move(faces);
  return collapsed;
}


// Cells that are large polygons are cut into quads by the diagonals that give the
// best-shaped quads, if every quad angle is within [min_angle, 180° − min_angle]:
// - a cell that touches no boundary and has 6 or 8 sides (where the curves fan out around a
//   singularity of the guidance): 2 or 3 quads, the singularity then a vertex of valence 3 or
//   5, as in any quad mesh; failing that 3 or 4 quads around a centre vertex (CentreSplit);
// - a boundary cell of 6 to 10 sides (a level line that turned back near the boundary):
//   quads, plus one triangle cut off at a boundary vertex if the number of sides is odd (so
//   that every cell off the boundary stays a quad); no diagonal
//   joins two boundary vertices. A large unbraced panel is both hard to make planar and
//   the softest part of the frame.
// Returns the number of interior and of boundary cells cut.
std::pair<int, int> SplitLargePolygons(double min_angle, Polygons* m, double min_edge) {
  std::set<std::pair<int, int>> halfedges;
  for (const auto& face : m->faces)
    for (size_t k = 0; k < face.size(); ++k) halfedges.insert({face[k], face[(k + 1) % face.size()]});
  std::vector<char> on_boundary(m->position.size(), 0);
  for (const auto& [a, b] : halfedges)
    if (!halfedges.count({b, a})) on_boundary[a] = on_boundary[b] = 1;
  std::vector<std::vector<int>> faces;
  std::pair<int, int> split{0, 0};
  for (auto& face : m->faces) {
    const size_t n = face.size();
    bool touches_boundary = false;
    for (const int v : face) touches_boundary |= on_boundary[v] != 0;
    std::vector<std::vector<std::vector<int>>> options;
    if (!touches_boundary && (n == 6 || n == 8)) {
      Quadrangulations(face, &options);
    } else if (touches_boundary && n >= 6 && n <= 10 && n % 2 == 0) {
      Quadrangulations(face, &options);
    } else if (touches_boundary && n >= 7 && n <= 9) {
      for (size_t i = 0; i < n; ++i) {  // a boundary corner face[i] cut off as a triangle, the rest in quads
        if (!on_boundary[face[i]]) continue;  // the triangle must stay a boundary cell
        const std::vector<int> ear{face[(i + n - 1) % n], face[i], face[(i + 1) % n]};
        std::vector<int> rest;
        for (size_t k = 1; k < n; ++k) rest.push_back(face[(i + k) % n]);
        std::vector<std::vector<std::vector<int>>> quads;
        Quadrangulations(rest, &quads);
        for (auto& cut : quads) {
          cut.push_back(ear);
          options.push_back(std::move(cut));
        }
      }
    }
    // A boundary cell of seven or more sides takes its best cut down to kLastResortCutAngle:
    // a quad with a 13° corner is a poor panel, a 10 m × 5 m 9-gon is no panel (the Great
    // Court's paper layout had one whose best cut was 12.9°, 2026-12-06).
    const bool large = touches_boundary && n >= 7;
    double best_score = large ? std::min(min_angle, kLastResortCutAngle) : min_angle;
    const std::vector<std::vector<int>>* best = nullptr;
    for (const auto& pieces : options) {
      const double score = CutScore(*m, face, pieces, halfedges, touches_boundary ? &on_boundary : nullptr);
      if (score >= best_score) best_score = score, best = &pieces;
    }
    if (best == nullptr && !touches_boundary && (n == 6 || n == 8) &&
        (CentreSplit(face, halfedges, min_angle, min_edge, m, &faces) ||
         (n == 8 && QuadAndCentreSplit(face, halfedges, min_angle, min_edge, m, &faces)))) {
      ++split.first;
    } else if (best == nullptr) {
      faces.push_back(std::move(face));
    } else {
      for (const auto& piece : *best) faces.push_back(piece);
      ++(touches_boundary ? split.second : split.first);
    }
  }
  m->faces = std::move(faces);
  return split;
}

}  // namespace pqlayout::extraction_internal
