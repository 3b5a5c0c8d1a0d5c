#include "geometry/closest_point.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <limits>

namespace pqlayout {
namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 ToCgal(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

struct ClosestPointQuery::Tree {
  std::vector<Triangle> triangles;
  std::vector<Eigen::Vector3d> normals;
  pqlayout::Tree tree;
};

ClosestPointQuery::ClosestPointQuery(const SurfaceModel& surface) : tree_(std::make_unique<Tree>()) {
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    tree_->triangles.emplace_back(ToCgal(surface.position(ids[0])), ToCgal(surface.position(ids[1])),
                                  ToCgal(surface.position(ids[2])));
    tree_->normals.push_back(surface.face_normal(f));
  }
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
  for (const auto& loop : surface.boundary_loops())
    for (size_t i = 0; i < loop.vertices.size(); ++i)
      boundary_edges_.emplace_back(surface.position(loop.vertices[i]),
                                   surface.position(loop.vertices[(i + 1) % loop.vertices.size()]));
}

ClosestPointQuery::~ClosestPointQuery() = default;

SurfacePoint ClosestPointQuery::OnSurface(const Eigen::Vector3d& p) const {
  const auto hit = tree_->tree.closest_point_and_primitive(ToCgal(p));
  SurfacePoint out;
  out.point = Eigen::Vector3d(hit.first.x(), hit.first.y(), hit.first.z());
  out.element = static_cast<int>(hit.second - tree_->triangles.cbegin());
  out.normal = tree_->normals[out.element];
  out.distance = (out.point - p).norm();
  return out;
}

SurfacePoint ClosestPointQuery::OnBoundary(const Eigen::Vector3d& p) const {
  SurfacePoint out;
  out.distance = std::numeric_limits<double>::infinity();
  for (size_t e = 0; e < boundary_edges_.size(); ++e) {
    const auto& [a, b] = boundary_edges_[e];
    const Eigen::Vector3d ab = b - a;
    const double t_line = (p - a).dot(ab) / ab.squaredNorm();
    const double t = std::clamp(t_line, 0.0, 1.0);
    const Eigen::Vector3d q = a + t * ab;
    const double d = (q - p).norm();
    if (d < out.distance) {
      out.distance = d;
      out.point = q;
      out.tangent = ab.normalized();
      out.element = static_cast<int>(e);
      out.inside_edge = t_line > 0.0 && t_line < 1.0;
    }
  }
  return out;
}

}  // namespace pqlayout
