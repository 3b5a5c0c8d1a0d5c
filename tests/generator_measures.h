// Measurements of generated triangle meshes, computed from the vertex positions alone:
// shared by tests/surface_generators_test.cc and tests/roof_generators_test.cc.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/mesh.h"
#include "geometry/surface_generators.h"

namespace pqlayout {

constexpr double kDegree = M_PI / 180.0;

inline Eigen::Vector3d Corner(const TriMesh& mesh, FaceHandle f, int k) {
  auto it = mesh.cfv_begin(f);
  for (int i = 0; i < k; ++i) ++it;
  return ToEigen(mesh.point(*it));
}

inline double Angle(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

struct MeshMeasures {
  double area = 0.0;
  double min_angle = M_PI;  // radians, in space
  double max_edge = 0.0;
  double min_normal_z = 1.0;  // z of the unit normal from the face's vertex order
};

inline MeshMeasures Measure(const TriMesh& mesh) {
  MeshMeasures m;
  for (FaceHandle f : mesh.faces()) {
    const Eigen::Vector3d p[3] = {Corner(mesh, f, 0), Corner(mesh, f, 1), Corner(mesh, f, 2)};
    const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
    m.area += 0.5 * normal.norm();
    m.min_normal_z = std::min(m.min_normal_z, normal.normalized().z());
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
      m.min_angle = std::min(m.min_angle, Angle(u, v));
      m.max_edge = std::max(m.max_edge, u.norm());
    }
  }
  return m;
}

inline int EulerCharacteristic(const TriMesh& mesh) {
  return static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) +
         static_cast<int>(mesh.n_faces());
}

inline int CountBoundaryLoops(const TriMesh& mesh) {
  std::vector<bool> visited(mesh.n_halfedges(), false);
  int loops = 0;
  for (HalfedgeHandle start : mesh.halfedges()) {
    if (!mesh.is_boundary(start) || visited[start.idx()]) continue;
    ++loops;
    for (HalfedgeHandle h = start; !visited[h.idx()]; h = mesh.next_halfedge_handle(h)) {
      visited[h.idx()] = true;
    }
  }
  return loops;
}

inline bool HasVertexAt(const TriMesh& mesh, double x, double y) {
  for (VertexHandle v : mesh.vertices()) {
    if (mesh.point(v)[0] == x && mesh.point(v)[1] == y) return true;
  }
  return false;
}

inline double MaxHeightError(const TriMesh& mesh, const std::function<double(double, double)>& f) {
  double error = 0.0;
  for (VertexHandle v : mesh.vertices()) {
    const OpenMesh::Vec3d& p = mesh.point(v);
    error = std::max(error, std::abs(p[2] - f(p[0], p[1])));
  }
  return error;
}

inline TriMesh Generate(const GeneratorParams& params) {
  TriMesh mesh;
  const Status status = GenerateSurface(params, &mesh);
  EXPECT_TRUE(status.ok()) << status.message();
  return mesh;
}

inline GeneratorParams Params(const std::string& name, double edge_length = 1.0) {
  GeneratorParams params;
  params.name = name;
  params.edge_length = edge_length;
  return params;
}

}  // namespace pqlayout
