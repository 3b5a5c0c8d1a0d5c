#include "geometry/closest_point.h"

#include <CGAL/AABB_segment_primitive.h>
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
using Segment = Kernel::Segment_3;
using Iterator = std::vector<Triangle>::const_iterator;
using SegmentIterator = std::vector<Segment>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_segment_primitive<Kernel, SegmentIterator>>>;

Kernel::Point_3 ToCgal(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// The closest (point, primitive) of q in tree over items; hint: an index into items or -1.
template <typename AabbTree, typename Item>
auto Closest(const AabbTree& tree, const std::vector<Item>& items, const Kernel::Point_3& q, int hint) {
  if (hint < 0 || hint >= static_cast<int>(items.size())) return tree.closest_point_and_primitive(q);
  return tree.closest_point_and_primitive(
      q, {Kernel().construct_projected_point_3_object()(items[hint], q), items.cbegin() + hint});
}
}  // namespace

struct ClosestPointQuery::Tree {
  std::vector<Triangle> triangles;
  std::vector<Eigen::Vector3d> normals;
  pqlayout::Tree tree;
  std::vector<Segment> segments;  // boundary edges
  SegmentTree boundary;
};

ClosestPointQuery::Geometry ClosestPointQuery::Gather(const SurfaceModel& surface) {
  Geometry g;
  g.triangles.reserve(surface.num_faces());
  g.normals.reserve(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    g.triangles.push_back({surface.position(ids[0]), surface.position(ids[1]), surface.position(ids[2])});
    g.normals.push_back(surface.face_normal(f));
  }
  for (const auto& loop : surface.boundary_loops())
    for (size_t i = 0; i < loop.vertices.size(); ++i)
      g.boundary.emplace_back(surface.position(loop.vertices[i]), surface.position(loop.vertices[(i + 1) % loop.vertices.size()]));
  return g;
}

ClosestPointQuery::ClosestPointQuery(const SurfaceModel& surface) : ClosestPointQuery(Gather(surface)) {}

ClosestPointQuery::ClosestPointQuery(const Geometry& g) : tree_(std::make_unique<Tree>()) {
  tree_->triangles.reserve(g.triangles.size());
  for (const auto& t : g.triangles) tree_->triangles.emplace_back(ToCgal(t[0]), ToCgal(t[1]), ToCgal(t[2]));
  tree_->normals = g.normals;
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
  for (const auto& [a, b] : g.boundary) tree_->segments.emplace_back(ToCgal(a), ToCgal(b));
  if (!tree_->segments.empty()) {
    tree_->boundary.insert(tree_->segments.cbegin(), tree_->segments.cend());
    tree_->boundary.build();
    tree_->boundary.accelerate_distance_queries();
  }
}

ClosestPointQuery::~ClosestPointQuery() = default;

SurfacePoint ClosestPointQuery::OnSurface(const Eigen::Vector3d& p, int hint) const {
  const auto hit = Closest(tree_->tree, tree_->triangles, ToCgal(p), hint);
  SurfacePoint out;
  out.point = Eigen::Vector3d(hit.first.x(), hit.first.y(), hit.first.z());
  out.element = static_cast<int>(hit.second - tree_->triangles.cbegin());
  out.normal = tree_->normals[out.element];
  out.distance = (out.point - p).norm();
  return out;
}

SurfacePoint ClosestPointQuery::OnBoundary(const Eigen::Vector3d& p, int hint) const {
  SurfacePoint out;
  out.distance = std::numeric_limits<double>::infinity();
  if (tree_->segments.empty()) return out;
  const auto hit = Closest(tree_->boundary, tree_->segments, ToCgal(p), hint);
  out.element = static_cast<int>(hit.second - tree_->segments.cbegin());
  const Segment& s = tree_->segments[out.element];
  const Eigen::Vector3d a(s.source().x(), s.source().y(), s.source().z()), b(s.target().x(), s.target().y(), s.target().z());
  // The parameter along the edge decides inside vs end (the tree's point is the same point).
  const Eigen::Vector3d ab = b - a;
  const double t_line = (p - a).dot(ab) / ab.squaredNorm();
  out.point = a + std::clamp(t_line, 0.0, 1.0) * ab;
  out.tangent = ab.normalized();
  out.inside_edge = t_line > 0.0 && t_line < 1.0;
  out.distance = (out.point - p).norm();
  return out;
}

Eigen::Vector3d TriangleBarycentric(const SurfaceModel& s, int face, const Eigen::Vector3d& p) {
  const auto ids = s.face_vertices(face);
  const Eigen::Vector3d a = s.position(ids[0]), b = s.position(ids[1]), c = s.position(ids[2]);
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area2 = n.squaredNorm();
  if (!(area2 > 0.0)) return Eigen::Vector3d(1.0, 0.0, 0.0);
  return Eigen::Vector3d((c - b).cross(p - b).dot(n), (a - c).cross(p - c).dot(n), (b - a).cross(p - a).dot(n)) /
         area2;
}

}  // namespace pqlayout
