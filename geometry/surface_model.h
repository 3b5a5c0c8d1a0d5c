// SurfaceModel: the reference triangle surface shared by every stage, with its derived
// quantities computed once at construction (face areas and unit normals, lumped vertex
// areas, boundary loops with inner/outer classification). Positions never change after
// construction; stages attach their per-element results as named OpenMesh properties
// (see VertexField / FaceField), which the field writers export by name.
#pragma once

#include <future>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <OpenMesh/Core/Utils/PropertyManager.hh>

#include "geometry/mesh.h"

namespace pqlayout {

struct BoundaryLoop {
  std::vector<VertexHandle> vertices;  // in order along the boundary halfedges
  double length = 0.0;                 // metres
  Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();  // ½ Σ p_i × p_{i+1}
  bool is_outer = false;  // the loop with the largest |vector area| is the outer one
};

class ClosestPointQuery;

class SurfaceModel {
 public:
  // Takes a valid triangle mesh (see ValidateSurfaceMesh); computes all cached quantities.
  // OpenMesh's meshes have no move constructor (a user-declared virtual destructor), so a
  // TriMesh passed on is copied (0.1–0.2 s at 1M triangles): the reference is handed over on the heap.
  explicit SurfaceModel(std::unique_ptr<TriMesh> mesh);
  explicit SurfaceModel(const TriMesh& mesh) : SurfaceModel(std::make_unique<TriMesh>(mesh)) {}

  const TriMesh& mesh() const { return mesh_; }
  // Non-const access is for attaching named per-element fields only; never move vertices.
  TriMesh& mesh() { return mesh_; }

  int num_vertices() const { return static_cast<int>(mesh_.n_vertices()); }
  int num_faces() const { return static_cast<int>(mesh_.n_faces()); }

  Eigen::Vector3d position(VertexHandle v) const { return ToEigen(mesh_.point(v)); }
  Eigen::Vector3d position(int v) const { return position(VertexHandle(v)); }
  // The three vertex indices of face f in its orientation.
  std::array<int, 3> face_vertices(int f) const { return face_vertices_[f]; }

  double face_area(int f) const { return face_area_[f]; }
  const Eigen::Vector3d& face_normal(int f) const { return face_normal_[f]; }
  // Lumped (barycentric) area: one third of the areas of the triangles at vertex v.
  double vertex_area(int v) const { return vertex_area_[v]; }
  double total_area() const { return total_area_; }

  const std::vector<BoundaryLoop>& boundary_loops() const { return loops_; }
  // Index into boundary_loops() of the loop through v, or -1 for an interior vertex.
  int boundary_loop_of(int v) const { return vertex_loop_[v]; }
  bool is_boundary(int v) const { return vertex_loop_[v] >= 0; }
  int num_boundary_vertices() const;

  // Boundary vertices where the boundary turns by more than min_turning_angle (radians),
  // e.g. the four corners of the Great Court rectangle.
  std::vector<int> BoundaryCorners(double min_turning_angle) const;

  // Closest points on this surface and its boundary (geometry/closest_point.h), indexed on
  // first use and then shared by every stage that asks (levelset, extract, planarize,
  // stiffen): a million triangles take ~1 s to index. Positions never change, so it never goes
  // stale. Not safe for a concurrent first call; the stages call it from one thread.
  const ClosestPointQuery& closest_points() const;
  // Starts indexing on a thread of its own (the positions copied first, on this thread), so
  // that closest_points() later finds it built or waits for it: the pipeline starts it after
  // the surface stage, and the ~1.2 s at a million triangles overlaps the membrane and guidance.
  // The same trees, so the same answers.
  void IndexClosestPointsInBackground() const;

  Eigen::Vector3d bbox_min() const { return bbox_min_; }
  Eigen::Vector3d bbox_max() const { return bbox_max_; }

  // Named per-element fields (created on first use, shared by name afterwards).
  template <typename T>
  OpenMesh::VProp<T> VertexField(const std::string& name) {
    CheckNotFrozen(OpenMesh::hasProperty<OpenMesh::VertexHandle, T>(mesh_, name.c_str()), name);
    return OpenMesh::VProp<T>(mesh_, name.c_str());
  }
  // A named double vertex field's values by vertex index (zeros if no stage set it).
  std::vector<double> VertexFieldValues(const std::string& name) {
    auto property = VertexField<double>(name);
    std::vector<double> values(num_vertices());
    for (int v = 0; v < num_vertices(); ++v) values[v] = property[VertexHandle(v)];
    return values;
  }
  template <typename T>
  OpenMesh::FProp<T> FaceField(const std::string& name) {
    CheckNotFrozen(OpenMesh::hasProperty<OpenMesh::FaceHandle, T>(mesh_, name.c_str()), name);
    return OpenMesh::FProp<T>(mesh_, name.c_str());
  }
  // Creates the named vertex fields (double) and then allows no new field: creating one changes
  // the mesh's list of properties, which another thread reading the mesh (a figure drawn on the
  // background writer) must not see change under it. Filling an existing field's values is
  // still allowed (no reader reads them). A new field asked for after this is a programming
  // error (CHECK).
  void FreezeFields(const std::vector<std::string>& vertex_fields);

 private:
  void CheckNotFrozen(bool exists, const std::string& name) const;
  void ComputeFaceQuantities();
  void ComputeBoundaryLoops();

  std::unique_ptr<TriMesh> owned_;
  TriMesh& mesh_;  // *owned_
  std::vector<std::array<int, 3>> face_vertices_;
  std::vector<double> face_area_;
  std::vector<Eigen::Vector3d> face_normal_;
  std::vector<double> vertex_area_;
  double total_area_ = 0.0;
  std::vector<BoundaryLoop> loops_;
  std::vector<int> vertex_loop_;
  Eigen::Vector3d bbox_min_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_max_ = Eigen::Vector3d::Zero();
  mutable std::shared_ptr<const ClosestPointQuery> closest_points_;
  mutable std::shared_future<std::shared_ptr<const ClosestPointQuery>> indexing_;  // IndexClosestPointsInBackground's
  bool fields_frozen_ = false;
};

}  // namespace pqlayout
