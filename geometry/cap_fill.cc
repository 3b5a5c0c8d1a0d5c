#include "geometry/cap_fill.h"

#include <algorithm>
#include <map>
#include <set>

namespace pqlayout {
namespace {

// The boundary loops of a polygon mesh, each as the to-vertices of its boundary halfedges in
// their order (the order a face closing the loop must have to match its neighbours).
std::vector<std::vector<int>> BoundaryLoops(const PolyMesh& mesh) {
  std::vector<char> seen(mesh.n_halfedges(), 0);
  std::vector<std::vector<int>> loops;
  for (const auto start : mesh.halfedges()) {
    if (!mesh.is_boundary(start) || seen[start.idx()]) continue;
    std::vector<int> loop;
    auto he = start;
    do {
      seen[he.idx()] = 1;
      loop.push_back(mesh.to_vertex_handle(he).idx());
      he = mesh.next_halfedge_handle(he);
    } while (he != start && loop.size() <= mesh.n_halfedges());
    loops.push_back(std::move(loop));
  }
  return loops;
}

// The directed edges of `faces` whose reverse none of them has, chained into one loop; empty
// if they do not form exactly one.
std::vector<int> OuterLoop(const std::vector<const std::vector<int>*>& faces) {
  std::set<std::pair<int, int>> edges;
  for (const auto* face : faces)
    for (size_t k = 0; k < face->size(); ++k) edges.insert({(*face)[k], (*face)[(k + 1) % face->size()]});
  std::map<int, int> next;
  for (const auto& [a, b] : edges)
    if (!edges.count({b, a}) && !next.emplace(a, b).second) return {};  // pinched
  if (next.empty()) return {};
  std::vector<int> loop;
  int v = next.begin()->first;
  do {
    loop.push_back(v);
    const auto it = next.find(v);
    if (it == next.end() || loop.size() > next.size()) return {};
    v = it->second;
  } while (v != loop.front());
  return loop.size() == next.size() ? loop : std::vector<int>();
}

// The first row of cells round cap c, if it lies within `row` of the cap's rim (every vertex
// of the cell within `row` of a rim vertex: the first ring line runs close to the hole, its
// cells are slivers, and the short-edge collapse turns some into triangles), merged into the
// cap, whose rim then is that ring line. Nothing changes if the union is not one disc.
void AbsorbThinRow(const PolyMesh& mesh, double row, size_t first_cap, size_t c,
                   std::vector<std::vector<int>>* faces, std::vector<QuadMeshVertex>* origin) {
  std::vector<int>& cap = (*faces)[c];
  const std::set<int> rim(cap.begin(), cap.end());
  const auto near_rim = [&](int v) {
    if (rim.count(v)) return true;
    for (const int r : rim)
      if ((ToEigen(mesh.point(VertexHandle(v))) - ToEigen(mesh.point(VertexHandle(r)))).norm() <= row) return true;
    return false;
  };
  std::set<std::pair<int, int>> cap_edges;
  for (size_t k = 0; k < cap.size(); ++k) cap_edges.insert({cap[(k + 1) % cap.size()], cap[k]});
  std::vector<size_t> absorbed;
  for (size_t f = 0; f < first_cap; ++f) {
    const std::vector<int>& face = (*faces)[f];
    bool shares = false, near = true;
    for (size_t k = 0; k < face.size(); ++k) {
      shares = shares || cap_edges.count({face[k], face[(k + 1) % face.size()]});
      near = near && near_rim(face[k]);
    }
    if (shares && near) absorbed.push_back(f);
  }
  if (absorbed.empty()) return;
  std::vector<const std::vector<int>*> parts = {&cap};
  for (const size_t f : absorbed) parts.push_back(&(*faces)[f]);
  std::vector<int> loop = OuterLoop(parts);
  if (loop.size() < 5) return;
  for (const size_t f : absorbed) (*faces)[f].clear();
  for (const int v : loop) (*origin)[v].cap = true, (*origin)[v].on_boundary = (*origin)[v].corner = false;
  cap = std::move(loop);
}

}  // namespace

int FillCaps(const std::vector<CapHole>& caps, double reach, double row, ExtractedMesh* out) {
  if (caps.empty()) return 0;
  PolyMesh& mesh = out->mesh;
  std::vector<std::vector<int>> faces;
  for (const auto f : mesh.faces()) {
    std::vector<int> face;
    for (const auto v : mesh.fv_range(f)) face.push_back(v.idx());
    faces.push_back(std::move(face));
  }
  const size_t first_cap = faces.size();
  for (const auto& loop : BoundaryLoops(mesh)) {
    for (const CapHole& cap : caps) {
      const bool inside = std::all_of(loop.begin(), loop.end(), [&](int v) {
        return (ToEigen(mesh.point(VertexHandle(v))) - cap.centre).norm() < cap.radius + reach;
      });
      if (!inside || loop.size() < 3) continue;
      faces.push_back(loop);
      for (const int v : loop) out->origin[v].on_boundary = out->origin[v].corner = false, out->origin[v].cap = true;
      break;
    }
  }
  if (faces.size() == first_cap) return 0;
  for (size_t c = first_cap; c < faces.size(); ++c) AbsorbThinRow(mesh, row, first_cap, c, &faces, &out->origin);
  // Loop vertices on the cap and one other face only: dropped from both (if both keep ≥ 3).
  std::vector<int> uses(mesh.n_vertices(), 0);
  for (const auto& face : faces)
    for (const int v : face) ++uses[v];
  for (size_t c = first_cap; c < faces.size(); ++c) {
    for (const int v : std::vector<int>(faces[c])) {
      if (uses[v] != 2) continue;
      const auto other = std::find_if(faces.begin(), faces.begin() + first_cap, [&](const std::vector<int>& face) {
        return std::find(face.begin(), face.end(), v) != face.end();
      });
      if (other == faces.begin() + first_cap || other->size() <= 3 || faces[c].size() <= 3) continue;
      other->erase(std::find(other->begin(), other->end(), v));
      faces[c].erase(std::find(faces[c].begin(), faces[c].end(), v));
      uses[v] = 0;
    }
  }
  // Rebuilt without the dropped vertices.
  std::vector<int> index(mesh.n_vertices(), -1);
  PolyMesh rebuilt;
  std::vector<QuadMeshVertex> origin;
  for (int v = 0; v < static_cast<int>(mesh.n_vertices()); ++v) {
    if (uses[v] == 0) continue;
    index[v] = rebuilt.add_vertex(mesh.point(VertexHandle(v))).idx();
    origin.push_back(out->origin[v]);
  }
  for (const auto& face : faces) {
    if (face.empty()) continue;  // absorbed into a cap
    std::vector<VertexHandle> handles;
    for (const int v : face) handles.push_back(VertexHandle(index[v]));
    if (!rebuilt.add_face(handles).is_valid()) ++out->stats.rejected_faces;
  }
  mesh = std::move(rebuilt);
  out->origin = std::move(origin);
  return static_cast<int>(faces.size() - first_cap);
}

bool IsCapFace(const ExtractedMesh& mesh, FaceHandle f) {
  int sides = 0;
  for (const auto v : mesh.mesh.fv_range(f)) {
    if (!mesh.origin[v.idx()].cap) return false;
    ++sides;
  }
  return sides > 4;
}

}  // namespace pqlayout
