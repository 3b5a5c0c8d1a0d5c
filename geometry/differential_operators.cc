#include "geometry/differential_operators.h"

#include <numeric>

namespace pqlayout {

std::array<Eigen::Vector3d, 3> FaceBasisGradients(const SurfaceModel& surface, int f) {
  const auto ids = surface.face_vertices(f);
  const Eigen::Vector3d& n = surface.face_normal(f);
  const double twice_area = 2.0 * surface.face_area(f);
  std::array<Eigen::Vector3d, 3> gradients;
  for (int k = 0; k < 3; ++k) {
    // ∇φ_k = n × e_k / (2A), e_k the edge opposite vertex k, oriented with the face.
    const Eigen::Vector3d e = surface.position(ids[(k + 2) % 3]) - surface.position(ids[(k + 1) % 3]);
    gradients[k] = n.cross(e) / twice_area;
  }
  return gradients;
}

Eigen::Vector3d FaceGradient(const SurfaceModel& surface, int f, const std::vector<double>& values) {
  const auto ids = surface.face_vertices(f);
  const auto g = FaceBasisGradients(surface, f);
  return values[ids[0]] * g[0] + values[ids[1]] * g[1] + values[ids[2]] * g[2];
}

Eigen::SparseMatrix<double> CotanStiffness(const SurfaceModel& surface) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(9 * surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    const auto g = FaceBasisGradients(surface, f);
    const double area = surface.face_area(f);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) triplets.emplace_back(ids[a], ids[b], area * g[a].dot(g[b]));
  }
  Eigen::SparseMatrix<double> K(surface.num_vertices(), surface.num_vertices());
  K.setFromTriplets(triplets.begin(), triplets.end());
  return K;
}

int ConnectedComponents(const SurfaceModel& surface, std::vector<int>* component) {
  std::vector<int> parent(surface.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    parent[find(ids[0])] = find(ids[1]);
    parent[find(ids[1])] = find(ids[2]);
  }
  component->assign(surface.num_vertices(), -1);
  std::vector<int> id_of_root(surface.num_vertices(), -1);
  int count = 0;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const int root = find(v);
    if (id_of_root[root] < 0) id_of_root[root] = count++;
    (*component)[v] = id_of_root[root];
  }
  return count;
}

}  // namespace pqlayout
