#include "geometry/edge_bracing.h"

#include <algorithm>
#include <numeric>

#include "geometry/polygon_shape.h"

namespace pqlayout {

std::vector<std::vector<int>> FreeEdgeQuads(const std::vector<bool>& free, const PolyMesh& mesh) {
  // Union–find over the vertices, joined along free boundary edges: one set per free stretch
  // (the quads along it may alternate with boundary triangles, which do not break it).
  std::vector<int> parent(mesh.n_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  const auto free_edge = [&](HalfedgeHandle h) {
    const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
    return mesh.is_boundary(mesh.edge_handle(h)) && free[a] && free[b];
  };
  for (const auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    if (free_edge(h)) parent[root(mesh.from_vertex_handle(h).idx())] = root(mesh.to_vertex_handle(h).idx());
  }
  std::vector<std::vector<int>> groups;
  std::vector<int> group_of(mesh.n_vertices(), -1);
  for (const auto f : mesh.faces()) {
    if (mesh.valence(f) != 4) continue;
    for (const auto h : mesh.fh_range(f)) {
      if (!free_edge(h)) continue;
      int& g = group_of[root(mesh.from_vertex_handle(h).idx())];
      if (g < 0) {
        g = static_cast<int>(groups.size());
        groups.emplace_back();
      }
      groups[g].push_back(f.idx());
      break;
    }
  }
  return groups;
}

int CutQuads(const std::vector<int>& faces, ExtractedMesh* out) {
  const PolyMesh& mesh = out->mesh;
  std::vector<char> to_cut(mesh.n_faces(), 0);
  for (const int f : faces) to_cut[f] = 1;
  std::vector<Eigen::Vector3d> position;
  for (const auto v : mesh.vertices()) position.push_back(ToEigen(mesh.point(v)));
  std::vector<std::vector<int>> polygons;
  int cut = 0;
  for (const auto f : mesh.faces()) {
    std::vector<int> face;
    for (const auto v : mesh.fv_range(f)) face.push_back(v.idx());
    std::vector<std::vector<int>> pieces{face};
    if (face.size() == 4 && to_cut[f.idx()]) {
      const std::vector<std::vector<int>> by_02{{face[0], face[1], face[2]}, {face[2], face[3], face[0]}};
      const std::vector<std::vector<int>> by_13{{face[1], face[2], face[3]}, {face[3], face[0], face[1]}};
      const auto smallest = [&](const std::vector<std::vector<int>>& pair) {
        return std::min(ShapeAngle(position, pair[0]), ShapeAngle(position, pair[1]));
      };
      pieces = smallest(by_02) >= smallest(by_13) ? by_02 : by_13;
      ++cut;
    }
    polygons.insert(polygons.end(), pieces.begin(), pieces.end());
  }
  if (cut == 0) return 0;
  out->mesh = BuildPolyMesh(position, polygons, &out->stats.rejected_faces);
  out->stats.braced_quads += cut;
  return cut;
}

int BraceFreeEdges(const std::vector<bool>& free, ExtractedMesh* out) {
  std::vector<int> all;
  for (const auto& group : FreeEdgeQuads(free, out->mesh)) all.insert(all.end(), group.begin(), group.end());
  return CutQuads(all, out);
}

}  // namespace pqlayout
