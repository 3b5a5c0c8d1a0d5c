#include "geometry/surface_model.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/closest_point.h"

namespace pqlayout {

const ClosestPointQuery& SurfaceModel::closest_points() const {
  if (!closest_points_ && indexing_.valid()) {
    closest_points_ = indexing_.get();
    indexing_ = {};  // the thread's shared state goes
  }
  if (!closest_points_) closest_points_ = std::make_shared<const ClosestPointQuery>(*this);
  return *closest_points_;
}

void SurfaceModel::IndexClosestPointsInBackground() const {
  if (closest_points_ || indexing_.valid()) return;
  indexing_ = std::async(std::launch::async, [geometry = ClosestPointQuery::Gather(*this)]() mutable {
                const ClosestPointQuery::Geometry own = std::move(geometry);  // freed once the trees are built
                return std::make_shared<const ClosestPointQuery>(own);
              }).share();
}

void SurfaceModel::FreezeFields(const std::vector<std::string>& vertex_fields) {
  for (const std::string& name : vertex_fields) VertexField<double>(name);
  fields_frozen_ = true;
}

void SurfaceModel::CheckNotFrozen(bool exists, const std::string& name) const {
  CHECK(exists || !fields_frozen_) << "field '" << name << "' created after SurfaceModel::FreezeFields";
}

SurfaceModel::SurfaceModel(std::unique_ptr<TriMesh> mesh) : owned_(std::move(mesh)), mesh_(*owned_) {
  ComputeFaceQuantities();
  ComputeBoundaryLoops();
}

void SurfaceModel::ComputeFaceQuantities() {
  const int nf = num_faces();
  const int nv = num_vertices();
  face_vertices_.resize(nf);
  face_area_.resize(nf);
  face_normal_.resize(nf);
  vertex_area_.assign(nv, 0.0);
  total_area_ = 0.0;
  for (const auto f : mesh_.faces()) {
    std::array<int, 3> ids{};
    int k = 0;
    for (const auto v : mesh_.fv_range(f)) ids[k++] = v.idx();
    face_vertices_[f.idx()] = ids;
    const Eigen::Vector3d p0 = position(ids[0]);
    const Eigen::Vector3d cross = (position(ids[1]) - p0).cross(position(ids[2]) - p0);
    const double area = 0.5 * cross.norm();
    face_area_[f.idx()] = area;
    face_normal_[f.idx()] = cross.normalized();
    total_area_ += area;
    for (const int v : ids) vertex_area_[v] += area / 3.0;
  }
  bbox_min_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  bbox_max_ = -bbox_min_;
  for (const auto v : mesh_.vertices()) {
    bbox_min_ = bbox_min_.cwiseMin(position(v));
    bbox_max_ = bbox_max_.cwiseMax(position(v));
  }
}

void SurfaceModel::ComputeBoundaryLoops() {
  vertex_loop_.assign(num_vertices(), -1);
  std::vector<char> visited(mesh_.n_halfedges(), 0);
  for (const auto start : mesh_.halfedges()) {
    if (!mesh_.is_boundary(start) || visited[start.idx()]) continue;
    BoundaryLoop loop;
    auto h = start;
    do {
      visited[h.idx()] = 1;
      const VertexHandle from = mesh_.from_vertex_handle(h);
      const Eigen::Vector3d p = position(from);
      const Eigen::Vector3d q = position(mesh_.to_vertex_handle(h));
      loop.vertices.push_back(from);
      loop.length += (q - p).norm();
      loop.vector_area += 0.5 * p.cross(q);
      h = mesh_.next_halfedge_handle(h);
    } while (h != start);
    loops_.push_back(std::move(loop));
  }
  // Deterministic order: the outer loop (largest enclosed vector area) first, then holes
  // by decreasing size.
  std::stable_sort(loops_.begin(), loops_.end(), [](const BoundaryLoop& a, const BoundaryLoop& b) {
    return a.vector_area.norm() > b.vector_area.norm();
  });
  for (size_t i = 0; i < loops_.size(); ++i) {
    loops_[i].is_outer = (i == 0);
    for (const auto v : loops_[i].vertices) vertex_loop_[v.idx()] = static_cast<int>(i);
  }
}

int SurfaceModel::num_boundary_vertices() const {
  return static_cast<int>(std::count_if(vertex_loop_.begin(), vertex_loop_.end(),
                                        [](int l) { return l >= 0; }));
}

std::vector<int> SurfaceModel::BoundaryCorners(double min_turning_angle) const {
  std::vector<int> corners;
  for (const auto& loop : loops_) {
    const size_t n = loop.vertices.size();
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d prev = position(loop.vertices[(i + n - 1) % n]);
      const Eigen::Vector3d here = position(loop.vertices[i]);
      const Eigen::Vector3d next = position(loop.vertices[(i + 1) % n]);
      const Eigen::Vector3d in = (here - prev).normalized();
      const Eigen::Vector3d out = (next - here).normalized();
      const double turning = std::atan2(in.cross(out).norm(), in.dot(out));
      if (turning > min_turning_angle) corners.push_back(loop.vertices[i].idx());
    }
  }
  return corners;
}

}  // namespace pqlayout
