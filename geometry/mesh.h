// The shared mesh model: OpenMesh with double-precision points (never the default float
// traits), for the reference triangle surface (TriMesh) and for the layout's polygon
// meshes (PolyMesh), plus small conversions to Eigen.
#pragma once

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pqlayout {

struct DoubleTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;
using VertexHandle = OpenMesh::VertexHandle;
using FaceHandle = OpenMesh::FaceHandle;
using EdgeHandle = OpenMesh::EdgeHandle;
using HalfedgeHandle = OpenMesh::HalfedgeHandle;

inline Eigen::Vector3d ToEigen(const OpenMesh::Vec3d& p) { return {p[0], p[1], p[2]}; }
inline OpenMesh::Vec3d ToOpenMesh(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// The polygon mesh of `faces` (vertex indices into `position`); each face OpenMesh refuses
// (it would be non-manifold) is left out and counted in *rejected.
inline PolyMesh BuildPolyMesh(const std::vector<Eigen::Vector3d>& position,
                              const std::vector<std::vector<int>>& faces, int* rejected) {
  PolyMesh mesh;
  for (const auto& p : position) mesh.add_vertex(ToOpenMesh(p));
  for (const auto& face : faces) {
    std::vector<VertexHandle> handles;
    for (const int v : face) handles.push_back(VertexHandle(v));
    if (!mesh.add_face(handles).is_valid()) ++*rejected;
  }
  return mesh;
}

}  // namespace pqlayout
