#include "geometry/mesh_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pqlayout {

TriangleQuality MeasureTriangleQuality(const TriMesh& mesh) {
  TriangleQuality q;
  double min_angle = M_PI;
  for (const auto f : mesh.faces()) {
    Eigen::Vector3d p[3];
    int k = 0;
    for (const auto v : mesh.fv_range(f)) p[k++] = ToEigen(mesh.point(v));
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
      min_angle = std::min(min_angle, std::atan2(a.cross(b).norm(), a.dot(b)));
    }
    const Eigen::Vector3d cross = (p[1] - p[0]).cross(p[2] - p[0]);
    q.area += 0.5 * cross.norm();
    q.projected_area += 0.5 * std::abs(cross.z());
  }
  q.min_angle_deg = mesh.n_faces() ? min_angle * 180.0 / M_PI : 0.0;
  q.edge_min = std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (const auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    q.edge_min = std::min(q.edge_min, length);
    q.edge_max = std::max(q.edge_max, length);
    sum += length;
  }
  if (mesh.n_edges() == 0) q.edge_min = 0.0;
  else q.edge_mean = sum / static_cast<double>(mesh.n_edges());
  return q;
}

int CountFaces(const PolyMesh& mesh, int sides) {
  int n = 0;
  for (const auto f : mesh.faces()) n += static_cast<int>(mesh.valence(f)) == sides;
  return n;
}

double QuadFraction(const PolyMesh& mesh) {
  return mesh.n_faces() > 0 ? static_cast<double>(CountFaces(mesh, 4)) / mesh.n_faces() : 0.0;
}

}  // namespace pqlayout
