#include "geometry/seams.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <queue>
#include <set>
#include <string>

namespace pqlayout {
namespace {

// Mean face_weight of the faces at the edge of halfedge h (1 if none).
double EdgeWeight(const TriMesh& mesh, HalfedgeHandle h, const std::vector<double>& face_weight) {
  double weight = 0.0;
  int faces = 0;
  for (const auto side : {h, mesh.opposite_halfedge_handle(h)})
    if (mesh.face_handle(side).is_valid()) weight += face_weight[mesh.face_handle(side).idx()], ++faces;
  return faces > 0 ? weight / faces : 1.0;
}

// Dijkstra from `sources` to the nearest vertex with is_target; in between only interior,
// unblocked vertices and no boundary edges. Returns the chain source … target, or empty.
template <typename IsTarget>
std::vector<int> ShortestPath(const SurfaceModel& s, const std::vector<double>& face_weight, double floor,
                              const std::vector<int>& sources, const std::vector<char>& blocked,
                              const IsTarget& is_target) {
  const TriMesh& mesh = s.mesh();
  const int nv = s.num_vertices();
  std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
  std::vector<int> previous(nv, -1);
  std::vector<char> is_source(nv, 0);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (const int v : sources) {
    dist[v] = 0.0;
    is_source[v] = 1;
    queue.push({0.0, v});
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    if (!is_source[v] && is_target(v)) {
      std::vector<int> path;
      for (int u = v; u >= 0; u = previous[u]) path.push_back(u);
      std::reverse(path.begin(), path.end());
      return path;
    }
    if (!is_source[v] && s.is_boundary(v)) continue;  // only the target may be on the boundary
    for (const auto h : mesh.voh_range(VertexHandle(v))) {
      const int w = mesh.to_vertex_handle(h).idx();
      if (is_source[w] || mesh.is_boundary(mesh.edge_handle(h))) continue;
      if (blocked[w] || (s.is_boundary(w) && !is_target(w))) continue;
      const double cost = mesh.calc_edge_length(h) * (floor + EdgeWeight(mesh, h, face_weight));
      if (d + cost < dist[w]) {
        dist[w] = d + cost;
        previous[w] = v;
        queue.push({dist[w], w});
      }
    }
  }
  return {};
}

int Find(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// The seam edges of `paths` (original edge → (path, halfedge in the path's direction), -1 for
// no seam), after checking that every path is a chain of adjacent interior vertices, on no
// other path, ending on the boundary.
Status SeamEdgesOfPaths(const SurfaceModel& surface, const std::vector<std::vector<int>>& paths,
                        std::vector<std::pair<int, HalfedgeHandle>>* seam_of_edge) {
  const TriMesh& mesh = surface.mesh();
  const int nv = surface.num_vertices();
  std::vector<int> count(nv, 0);
  seam_of_edge->assign(mesh.n_edges(), {-1, HalfedgeHandle()});
  for (size_t p = 0; p < paths.size(); ++p) {
    const auto& path = paths[p];
    const std::string where = "seams: path " + std::to_string(p) + ": ";
    if (path.size() < 2) return Status::InvalidInput(where + "fewer than 2 vertices");
    for (const int v : path) {
      if (v < 0 || v >= nv) return Status::InvalidInput(where + "vertex " + std::to_string(v) + " out of range");
      if (++count[v] > 1) return Status::InvalidInput(where + "vertex " + std::to_string(v) + " is on two paths");
    }
    if (!surface.is_boundary(path.back())) return Status::InvalidInput(where + "does not end on the boundary");
    for (size_t k = 0; k + 1 < path.size(); ++k) {
      if (k > 0 && surface.is_boundary(path[k]))
        return Status::InvalidInput(where + "touches the boundary at vertex " + std::to_string(path[k]));
      const auto h = mesh.find_halfedge(VertexHandle(path[k]), VertexHandle(path[k + 1]));
      if (!h.is_valid()) return Status::InvalidInput(where + "vertices " + std::to_string(path[k]) + " and " +
                                                     std::to_string(path[k + 1]) + " are not adjacent");
      if (mesh.is_boundary(mesh.edge_handle(h))) return Status::InvalidInput(where + "runs along the boundary");
      (*seam_of_edge)[mesh.edge_handle(h).idx()] = {static_cast<int>(p), h};
    }
  }
  return Status::Ok();
}

// Corner 3f + k of face f where its k-th vertex is v; -1 if v is not a vertex of f.
int CornerOf(const SurfaceModel& surface, int f, int v) {
  const auto ids = surface.face_vertices(f);
  for (int k = 0; k < 3; ++k)
    if (ids[k] == v) return 3 * f + k;
  return -1;
}

// Union-find forest of the corners (3f + k), joined across every interior edge that is no
// seam; read the classes with Find.
std::vector<int> CornerClasses(const SurfaceModel& surface,
                               const std::vector<std::pair<int, HalfedgeHandle>>& seam_of_edge) {
  const TriMesh& mesh = surface.mesh();
  std::vector<int> parent(3 * surface.num_faces());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto e : mesh.edges()) {
    if (mesh.is_boundary(e) || seam_of_edge[e.idx()].first >= 0) continue;
    const auto h = mesh.halfedge_handle(e, 0), o = mesh.opposite_halfedge_handle(h);
    const int f = mesh.face_handle(h).idx(), g = mesh.face_handle(o).idx();
    for (const auto v : {mesh.from_vertex_handle(h), mesh.to_vertex_handle(h)})
      parent[Find(parent, CornerOf(surface, f, v.idx()))] = Find(parent, CornerOf(surface, g, v.idx()));
  }
  return parent;
}

// Adds face f (a, b, c) to the cut mesh with the original's corner order: its circulation
// starts at a.
Status AddFaceInOrder(int f, VertexHandle a, VertexHandle b, VertexHandle c, TriMesh* cut_mesh) {
  const auto face = cut_mesh->add_face(a, b, c);
  if (!face.is_valid() || face.idx() != f)
    return Status::Internal("seams: face " + std::to_string(f) + " could not be rebuilt in the cut surface");
  // Corner order as in the original: start the face's circulation at the right halfedge.
  for (const auto h : cut_mesh->fh_range(face)) {
    if (cut_mesh->to_vertex_handle(h) != a) continue;
    cut_mesh->set_halfedge_handle(face, h);
    break;
  }
  if (cut_mesh->fv_begin(face)->idx() != a.idx()) {
    for (const auto h : cut_mesh->fh_range(face)) {
      if (cut_mesh->from_vertex_handle(h) != a) continue;
      cut_mesh->set_halfedge_handle(face, h);
      break;
    }
  }
  return Status::Ok();
}

}  // namespace

std::vector<std::vector<int>> RouteSeams(const SurfaceModel& surface, const std::vector<double>& face_weight,
                                         const std::vector<int>& tips, double floor) {
  const int nv = surface.num_vertices();
  std::vector<char> blocked(nv, 0), used_end(nv, 0);
  for (const int t : tips) blocked[t] = 1;
  std::vector<std::vector<int>> paths;
  const auto take = [&](std::vector<int> path) {
    for (const int v : path) blocked[v] = 1;
    used_end[path.front()] = used_end[path.back()] = 1;
    paths.push_back(std::move(path));
  };
  for (const int tip : tips) {
    if (surface.is_boundary(tip)) continue;
    auto path = ShortestPath(surface, face_weight, floor, {tip}, blocked,
                             [&](int v) { return surface.is_boundary(v) && !used_end[v]; });
    if (path.size() >= 2) take(std::move(path));
  }
  const auto& loops = surface.boundary_loops();
  std::vector<char> joined(loops.size(), 0);
  for (size_t l = 0; l < loops.size(); ++l) joined[l] = loops[l].is_outer;
  for (size_t l = 0; l < loops.size(); ++l) {
    if (joined[l]) continue;
    std::vector<int> sources;
    for (const auto v : loops[l].vertices)
      if (!used_end[v.idx()]) sources.push_back(v.idx());
    auto path = ShortestPath(surface, face_weight, floor, sources, blocked, [&](int v) {
      const int loop = surface.boundary_loop_of(v);
      return loop >= 0 && loop != static_cast<int>(l) && joined[loop] && !used_end[v];
    });
    if (path.size() >= 2) take(std::move(path));
    joined[l] = 1;
  }
  return paths;
}

double PathWeight(const SurfaceModel& surface, const std::vector<double>& face_weight, const std::vector<int>& path) {
  const TriMesh& mesh = surface.mesh();
  double total = 0.0;
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const auto h = mesh.find_halfedge(VertexHandle(path[k]), VertexHandle(path[k + 1]));
    if (h.is_valid()) total += mesh.calc_edge_length(h) * EdgeWeight(mesh, h, face_weight);
  }
  return total;
}

Status SeamCut::Build(const SurfaceModel& surface, std::vector<std::vector<int>> paths,
                      std::unique_ptr<SeamCut>* out) {
  const TriMesh& mesh = surface.mesh();
  const int nv = surface.num_vertices(), nf = surface.num_faces();
  auto cut = std::make_unique<SeamCut>();
  // Seam edges: original edge → (path, halfedge in the path's direction).
  std::vector<std::pair<int, HalfedgeHandle>> seam_of_edge;
  PQ_RETURN_IF_ERROR(SeamEdgesOfPaths(surface, paths, &seam_of_edge));
  // Corners (3f + k) joined across every interior edge that is no seam: each class is a vertex
  // of the cut surface.
  const auto corner = [&](int f, int v) { return CornerOf(surface, f, v); };
  std::vector<int> parent = CornerClasses(surface, seam_of_edge);
  std::vector<int> vertex_of_class(3 * nf, -1), cut_vertex(3 * nf);
  cut->first_copy_.assign(nv, -1);
  TriMesh cut_mesh;
  for (int f = 0; f < nf; ++f) {
    const auto ids = surface.face_vertices(f);
    for (int k = 0; k < 3; ++k) {
      const int root = Find(parent, 3 * f + k);
      if (vertex_of_class[root] < 0) {
        vertex_of_class[root] = static_cast<int>(cut->original_vertex_.size());
        cut->original_vertex_.push_back(ids[k]);
        if (cut->first_copy_[ids[k]] < 0) cut->first_copy_[ids[k]] = vertex_of_class[root];
        cut_mesh.add_vertex(mesh.point(VertexHandle(ids[k])));
      }
      cut_vertex[3 * f + k] = vertex_of_class[root];
    }
  }
  for (int f = 0; f < nf; ++f) {
    PQ_RETURN_IF_ERROR(
        AddFaceInOrder(f, VertexHandle(cut_vertex[3 * f]), VertexHandle(cut_vertex[3 * f + 1]),
                       VertexHandle(cut_vertex[3 * f + 2]), &cut_mesh));
  }
  cut->cut_ = std::make_unique<SurfaceModel>(std::move(cut_mesh));
  const TriMesh& cm = cut->cut_->mesh();
  for (int f = 0; f < nf; ++f) {
    const auto ids = cut->cut_->face_vertices(f);
    for (int k = 0; k < 3; ++k)
      if (ids[k] != cut_vertex[3 * f + k])
        return Status::Internal("seams: corner order of face " + std::to_string(f) + " changed in the cut surface");
  }
  // Seam edges, seen from both sides, and the copy pairs of their vertices.
  cut->seam_of_cut_edge_.assign(cm.n_edges(), -1);
  std::set<std::tuple<int, int, int>> pairs;
  for (const auto e : mesh.edges()) {
    const auto [p, h] = seam_of_edge[e.idx()];
    if (p < 0) continue;
    SeamEdge edge;
    edge.path = p;
    edge.original_edge = e.idx();
    edge.minus_face = mesh.face_handle(h).idx();
    edge.plus_face = mesh.face_handle(mesh.opposite_halfedge_handle(h)).idx();
    const int from = mesh.from_vertex_handle(h).idx(), to = mesh.to_vertex_handle(h).idx();
    const auto cut_edge = [&](int f) {
      const auto k = cm.find_halfedge(VertexHandle(cut_vertex[corner(f, from)]), VertexHandle(cut_vertex[corner(f, to)]));
      const auto o = cm.find_halfedge(VertexHandle(cut_vertex[corner(f, to)]), VertexHandle(cut_vertex[corner(f, from)]));
      return (k.is_valid() ? cm.edge_handle(k) : cm.edge_handle(o)).idx();
    };
    edge.cut_edge_minus = cut_edge(edge.minus_face);
    edge.cut_edge_plus = cut_edge(edge.plus_face);
    cut->seam_of_cut_edge_[edge.cut_edge_minus] = cut->seam_of_cut_edge_[edge.cut_edge_plus] = p;
    cut->seam_edges_.push_back(edge);
    for (const int v : {from, to}) {
      const int minus = cut_vertex[corner(edge.minus_face, v)], plus = cut_vertex[corner(edge.plus_face, v)];
      if (pairs.insert({v, minus, plus}).second) cut->copy_pairs_.push_back({p, v, minus, plus});
    }
  }
  for (const auto& path : paths) cut->starts_inside_.push_back(!surface.is_boundary(path.front()));
  cut->paths_ = std::move(paths);
  *out = std::move(cut);
  return Status::Ok();
}

std::vector<double> SeamCut::ToCut(const std::vector<double>& original) const {
  std::vector<double> values(original_vertex_.size());
  for (size_t v = 0; v < values.size(); ++v) values[v] = original[original_vertex_[v]];
  return values;
}

std::vector<double> SeamCut::ToOriginal(const std::vector<double>& cut_values) const {
  std::vector<double> values(first_copy_.size());
  for (size_t v = 0; v < values.size(); ++v) values[v] = cut_values[first_copy_[v]];
  return values;
}

}  // namespace pqlayout
