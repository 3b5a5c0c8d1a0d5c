#include "geometry/edge_bracing.h"

#include <algorithm>

#include "geometry/polygon_shape.h"

namespace pqlayout {

int BraceFreeEdges(const std::vector<bool>& free, ExtractedMesh* out) {
  const PolyMesh& mesh = out->mesh;
  std::vector<Eigen::Vector3d> position;
  for (const auto v : mesh.vertices()) position.push_back(ToEigen(mesh.point(v)));
  std::vector<std::vector<int>> faces;
  int cut = 0;
  for (const auto f : mesh.faces()) {
    std::vector<int> face;
    for (const auto v : mesh.fv_range(f)) face.push_back(v.idx());
    bool on_free_edge = false;
    for (const auto h : mesh.fh_range(f)) {
      const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
      on_free_edge |= mesh.is_boundary(mesh.edge_handle(h)) && free[a] && free[b];
    }
    std::vector<std::vector<int>> pieces{face};
    if (face.size() == 4 && on_free_edge) {
      const std::vector<std::vector<int>> by_02{{face[0], face[1], face[2]}, {face[2], face[3], face[0]}};
      const std::vector<std::vector<int>> by_13{{face[1], face[2], face[3]}, {face[3], face[0], face[1]}};
      const auto smallest = [&](const std::vector<std::vector<int>>& pair) {
        return std::min(ShapeAngle(position, pair[0]), ShapeAngle(position, pair[1]));
      };
      pieces = smallest(by_02) >= smallest(by_13) ? by_02 : by_13;
      ++cut;
    }
    faces.insert(faces.end(), pieces.begin(), pieces.end());
  }
  if (cut == 0) return 0;
  out->mesh = BuildPolyMesh(position, faces, &out->stats.rejected_faces);
  out->stats.braced_quads += cut;
  return cut;
}

}  // namespace pqlayout
