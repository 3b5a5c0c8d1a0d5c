#include "geometry/differential_operators.h"

#include <algorithm>

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

// Assembled straight into K's compressed columns: the pattern (each vertex and its neighbours,
// sorted) first, then each face's nine products added into their slots, in face order, which is
// the order in which Eigen's setFromTriplets summed them: the same bits, in ~1/3 of the time at
// a million triangles (the membrane's assembly was 1.3 s there).
Eigen::SparseMatrix<double> CotanStiffness(const SurfaceModel& surface) {
  const int nv = surface.num_vertices(), nf = surface.num_faces();
  std::vector<int> outer(nv + 1, 0);
  for (int f = 0; f < nf; ++f)
    for (const int v : surface.face_vertices(f)) outer[v + 1] += 3;  // with repeats, trimmed below
  for (int v = 0; v < nv; ++v) outer[v + 1] += outer[v];
  std::vector<int> inner(outer[nv]), fill(outer.begin(), outer.end() - 1);
  for (int f = 0; f < nf; ++f) {
    const auto ids = surface.face_vertices(f);
    for (const int j : ids)
      for (const int i : ids) inner[fill[j]++] = i;
  }
  int nonzeros = 0;
  for (int j = 0; j < nv; ++j) {  // sort and deduplicate each column in place, compacting
    const auto begin = inner.begin() + outer[j], end = inner.begin() + outer[j + 1];
    std::sort(begin, end);
    const int count = static_cast<int>(std::unique(begin, end) - begin);
    outer[j] = nonzeros;
    std::copy(begin, begin + count, inner.begin() + nonzeros);
    nonzeros += count;
  }
  outer[nv] = nonzeros;
  inner.resize(nonzeros);
  std::vector<double> values(nonzeros, 0.0);
  std::vector<char> set(nonzeros, 0);  // a slot's first term is stored, not added to 0 (−0 stays −0)
  for (int f = 0; f < nf; ++f) {
    const auto ids = surface.face_vertices(f);
    const auto g = FaceBasisGradients(surface, f);
    const double area = surface.face_area(f);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const int column = ids[b];
        const int k = static_cast<int>(std::lower_bound(inner.begin() + outer[column], inner.begin() + outer[column + 1], ids[a]) - inner.begin());
        const double term = area * g[a].dot(g[b]);
        values[k] = set[k] ? values[k] + term : term;
        set[k] = 1;
      }
  }
  return Eigen::Map<const Eigen::SparseMatrix<double>>(nv, nv, nonzeros, outer.data(), inner.data(), values.data());
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
