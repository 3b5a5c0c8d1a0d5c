// CloseShortEdges, CutDarts, SplitFoldedPanels and SplitWarpedPanels (panel_repair.h).
#include "geometry/panel_repair.h"

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "geometry/planarity.h"
#include "geometry/polygon_shape.h"
#include "geometry/quad_cleanup.h"

namespace pqlayout {

// At most this many rounds of CollapseRound (each closes edges on disjoint neighbourhoods).
constexpr int kMaxRounds = 10;

namespace {

// The mesh's vertex positions, and one face's vertex indices.
std::vector<Eigen::Vector3d> Positions(const PolyMesh& mesh) {
  std::vector<Eigen::Vector3d> position;
  for (const auto v : mesh.vertices()) position.push_back(ToEigen(mesh.point(v)));
  return position;
}

std::vector<int> FaceVertices(const PolyMesh& mesh, FaceHandle f) {
  std::vector<int> face;
  for (const auto v : mesh.fv_range(f)) face.push_back(v.idx());
  return face;
}

// Replaces the mesh by `faces` over `position` (the vertices keep their numbers and origins).
void Rebuild(const std::vector<Eigen::Vector3d>& position, const std::vector<std::vector<int>>& faces,
             ExtractedMesh* mesh) {
  int rejected = 0;
  mesh->mesh = BuildPolyMesh(position, faces, &rejected);
  mesh->stats.rejected_faces += rejected;
}

// A chord (an interior edge between two vertices on the reference boundary) that
// planarisation shortened below min_length cuts off an ear: the triangle on its far side,
// whose two other edges are on the mesh boundary. The collapse rules refuse the chord (it
// would pinch the mesh), so the ear is dropped first — a sliver of roof at most min_length
// wide — and the chord, now on the boundary, closes like any boundary edge. Not when the
// ear's tip is a corner of the reference. Counted as closed edges.
int DropEarsOfShortChords(double min_length, extraction_internal::Polygons* m) {
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  for (size_t f = 0; f < m->faces.size(); ++f)
    for (size_t k = 0; k < m->faces[f].size(); ++k) {
      const int a = m->faces[f][k], b = m->faces[f][(k + 1) % m->faces[f].size()];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  const auto on_mesh_boundary = [&](int a, int b) { return edge_faces[{std::min(a, b), std::max(a, b)}].size() == 1; };
  std::vector<char> drop(m->faces.size(), 0);
  int dropped = 0;
  for (const auto& [e, faces] : edge_faces) {
    const auto [u, v] = e;
    if (faces.size() != 2 || !m->origin[u].on_boundary || !m->origin[v].on_boundary ||
        (m->position[u] - m->position[v]).norm() >= min_length)
      continue;
    for (const int f : faces) {
      const auto& t = m->faces[f];
      if (t.size() != 3 || drop[f]) continue;
      const int w = t[0] != u && t[0] != v ? t[0] : (t[1] != u && t[1] != v ? t[1] : t[2]);
      if (m->origin[w].corner || !on_mesh_boundary(u, w) || !on_mesh_boundary(w, v)) continue;
      drop[f] = 1, ++dropped;
      break;
    }
  }
  if (dropped == 0) return 0;
  std::vector<std::vector<int>> kept;
  for (size_t f = 0; f < m->faces.size(); ++f)
    if (!drop[f]) kept.push_back(std::move(m->faces[f]));
  m->faces = std::move(kept);
  return dropped;
}

}  // namespace

int CloseShortEdges(double min_length, ExtractedMesh* mesh, std::vector<Eigen::Vector3d>* start) {
  extraction_internal::Polygons now, then;
  now.position = Positions(mesh->mesh);
  now.origin = mesh->origin;
  for (const auto f : mesh->mesh.faces()) now.faces.push_back(FaceVertices(mesh->mesh, f));
  int closed = DropEarsOfShortChords(min_length, &now);
  for (int round = 0; round < kMaxRounds; ++round) {
    const int n = extraction_internal::CollapseRound(min_length, &now);
    if (n == 0) break;
    closed += n;
  }
  if (closed == 0) return 0;
  then.position = *start;
  then.origin = now.origin;
  then.faces = now.faces;
  extraction_internal::Compact(&now);  // the same renumbering for both: it follows the faces
  extraction_internal::Compact(&then);
  Rebuild(now.position, now.faces, mesh);
  mesh->origin = std::move(now.origin);
  *start = std::move(then.position);
  return closed;
}

int CutDarts(ExtractedMesh* mesh) {
  const std::vector<Eigen::Vector3d> position = Positions(mesh->mesh);
  std::vector<std::vector<int>> faces;
  int cut = 0;
  for (const auto f : mesh->mesh.faces()) {
    std::vector<int> face = FaceVertices(mesh->mesh, f);
    int reflex = -1, count = 0;
    if (face.size() == 4) {
      const std::vector<double> turns = CornerTurns(position, face, NewellNormal(position, face));
      for (int k = 0; k < 4; ++k)
        if (turns[k] < 0.0) reflex = k, ++count;
    }
    if (count != 1) {
      faces.push_back(std::move(face));
      continue;
    }
    const int r = reflex;
    faces.push_back({face[r], face[(r + 1) % 4], face[(r + 2) % 4]});
    faces.push_back({face[(r + 2) % 4], face[(r + 3) % 4], face[r]});
    ++cut;
  }
  if (cut == 0) return 0;
  Rebuild(position, faces, mesh);
  return cut;
}

namespace {

// The fan of `polygon` from its corner k.
std::vector<std::vector<int>> Fan(const std::vector<int>& polygon, size_t k) {
  std::vector<std::vector<int>> fan;
  const size_t m = polygon.size();
  for (size_t i = 1; i + 1 < m; ++i)
    fan.push_back({polygon[k], polygon[(k + i) % m], polygon[(k + i + 1) % m]});
  return fan;
}

// Every edge of the mesh as a (smaller, larger) vertex index pair.
std::set<std::pair<int, int>> Edges(const PolyMesh& mesh) {
  std::set<std::pair<int, int>> edges;
  for (const auto e : mesh.edges()) {
    const auto he = mesh.halfedge_handle(e, 0);
    const int a = mesh.from_vertex_handle(he).idx(), b = mesh.to_vertex_handle(he).idx();
    edges.insert({std::min(a, b), std::max(a, b)});
  }
  return edges;
}

bool IsEdge(const std::set<std::pair<int, int>>& edges, int a, int b) {
  return edges.count({std::min(a, b), std::max(a, b)}) > 0;
}

// The smallest corner angle of the triangles of a fan, radians; −1 if one of them faces
// against `normal` or is degenerate.
double SmallestAngle(const std::vector<Eigen::Vector3d>& position, const std::vector<std::vector<int>>& fan,
                     const Eigen::Vector3d& normal) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& t : fan) {
    if (!(normal.dot((position[t[1]] - position[t[0]]).cross(position[t[2]] - position[t[0]])) > 0.0)) return -1.0;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d u = (position[t[(i + 1) % 3]] - position[t[i]]).normalized();
      const Eigen::Vector3d w = (position[t[(i + 2) % 3]] - position[t[i]]).normalized();
      smallest = std::min(smallest, std::acos(std::clamp(u.dot(w), -1.0, 1.0)));
    }
  }
  return smallest;
}

// Cuts every face for which corner(face) returns k < its size into the fan from its corner k
// (Fan); the vertices stay. corner sees the positions and the mesh's edges (a diagonal that is
// an edge already would pinch the mesh). Returns the number of faces cut.
template <typename Corner>
int CutIntoFans(ExtractedMesh* mesh, Corner corner) {
  const std::vector<Eigen::Vector3d> position = Positions(mesh->mesh);
  const std::set<std::pair<int, int>> edges = Edges(mesh->mesh);
  std::vector<std::vector<int>> faces;
  int split = 0;
  for (const auto f : mesh->mesh.faces()) {
    std::vector<int> face = FaceVertices(mesh->mesh, f);
    const size_t k = corner(face, position, edges);
    if (k >= face.size()) {
      faces.push_back(std::move(face));
      continue;
    }
    for (auto& t : Fan(face, k)) faces.push_back(std::move(t));
    ++split;
  }
  if (split > 0) Rebuild(position, faces, mesh);
  return split;
}

}  // namespace

int SplitFoldedPanels(const std::vector<Eigen::Vector3d>& start, ExtractedMesh* mesh) {
  return CutIntoFans(mesh, [&](const std::vector<int>& face, const std::vector<Eigen::Vector3d>& now,
                               const std::set<std::pair<int, int>>& edges) {
    size_t best = face.size();
    if (face.size() < 4 || !FoldedSince(start, now, face)) return best;
    const Eigen::Vector3d n = NewellNormal(start, face);
    double best_area = -std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < face.size(); ++k) {
      double smallest = std::numeric_limits<double>::infinity();
      bool free = true;
      for (const auto& t : Fan(face, k))
        smallest = std::min(smallest, n.dot((now[t[1]] - now[t[0]]).cross(now[t[2]] - now[t[0]])));
      for (size_t i = 2; i + 2 <= face.size(); ++i) free = free && !IsEdge(edges, face[k], face[(k + i) % face.size()]);
      if (free && smallest > best_area) best_area = smallest, best = k;
    }
    return best;
  });
}

int SplitWarpedPanels(double max_delta, ExtractedMesh* mesh) {
  if (!(max_delta > 0.0)) return 0;
  return CutIntoFans(mesh, [&](const std::vector<int>& face, const std::vector<Eigen::Vector3d>& position,
                               const std::set<std::pair<int, int>>& edges) {
    size_t best = face.size();
    if (face.size() != 4 ||
        !(QuadPlanarityDelta(position[face[0]], position[face[1]], position[face[2]], position[face[3]]) > max_delta))
      return best;
    const Eigen::Vector3d n = NewellNormal(position, face);
    double best_angle = 0.0;
    for (size_t k = 0; k < 2; ++k) {
      const double angle = IsEdge(edges, face[k], face[k + 2]) ? -1.0 : SmallestAngle(position, Fan(face, k), n);
      if (angle > best_angle) best_angle = angle, best = k;
    }
    return best;
  });
}

}  // namespace pqlayout
