#include "geometry/closest_point.h"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
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

// The triangles' boxes in a uniform grid, to settle a hinted query without the tree. CGAL's
// hinted search starts from the hint's (point, triangle) and replaces it by any triangle whose
// projection is not farther and is another point (AABB_traits::Closest_point,
// Projection_traits::intersection). Settle looks at the triangles whose boxes meet the cube
// round the query of the hint's distance (any triangle that close has a point in that cube, and
// so is filed in a cell the cube covers), with CGAL's own constructions and comparisons: if none
// can displace the hint, the answer is the hint; if one is closer than the hint and every other
// by a margin far above rounding, the tree search ends there (it reaches that triangle, since its
// boxes are closer than any bound held before, and nothing displaces it after); else (ties, near
// ties, or a cube over many cells) the tree search runs as before. The same answer either way,
// to the bit. Why: a vertex sliding on a million-triangle reference asks ~170k hinted queries in
// planarisation, each tree search ~20 levels of cache misses (~4 µs).
class TriangleGrid {
 public:
  void Build(const std::vector<Triangle>& triangles);
  // Given the hint's (point `at`, triangle `hint`): true with the tree search's answer in them,
  // or false if it cannot be settled here (a near tie, or the cube too large to look).
  bool Settle(const std::vector<Triangle>& triangles, const Kernel::Point_3& q, Kernel::Point_3* at, int* hint) const;

 private:
  static constexpr int kMaxCells = 27;  // a larger cube: the tree search
  int Cell(double x, int axis) const {  // x finite; clamped before the cast (a far x overflows no int)
    return static_cast<int>(std::clamp(std::floor((x - lo_[axis]) / cell_), 0.0, n_[axis] - 1.0));
  }
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0, slack_ = 0.0;
  std::array<int, 3> n_{1, 1, 1};
  std::vector<int> offsets_, items_;            // triangles per cell (CSR)
  std::vector<std::array<float, 6>> boxes_;     // per triangle, rounded outwards
};

struct ClosestPointQuery::Tree {
  std::vector<Triangle> triangles;
  std::vector<Eigen::Vector3d> normals;
  pqlayout::Tree tree;
  TriangleGrid grid;
  std::vector<Segment> segments;  // boundary edges
  SegmentTree boundary;
};

void TriangleGrid::Build(const std::vector<Triangle>& triangles) {
  const size_t n = triangles.size();
  if (n == 0) return;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  double extent_sum = 0.0;
  boxes_.resize(n);
  for (size_t t = 0; t < n; ++t) {
    const CGAL::Bbox_3 b = triangles[t].bbox();
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], b.min(a)), hi[a] = std::max(hi[a], b.max(a));
      boxes_[t][a] = std::nextafter(static_cast<float>(b.min(a)), -INFINITY);
      boxes_[t][3 + a] = std::nextafter(static_cast<float>(b.max(a)), INFINITY);
    }
    extent_sum += std::max({b.xmax() - b.xmin(), b.ymax() - b.ymin(), b.zmax() - b.zmin()});
  }
  const Eigen::Vector3d extent = hi - lo;
  lo_ = lo;
  slack_ = 1e-9 * extent.norm() + 1e-300;
  cell_ = std::max(2.0 * extent_sum / n, 1e-9 * extent.maxCoeff() + 1e-300);
  const auto cells = [&] {
    double count = 1.0;
    for (int a = 0; a < 3; ++a) n_[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / cell_))), count *= n_[a];
    return count;
  };
  while (cells() > 2.0 * n + 8.0) cell_ *= 1.25;
  offsets_.assign(static_cast<size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
  const auto each_cell = [&](size_t t, const auto& visit) {
    const CGAL::Bbox_3 b = triangles[t].bbox();
    for (int k = Cell(b.zmin(), 2); k <= Cell(b.zmax(), 2); ++k)
      for (int j = Cell(b.ymin(), 1); j <= Cell(b.ymax(), 1); ++j)
        for (int i = Cell(b.xmin(), 0); i <= Cell(b.xmax(), 0); ++i) visit((static_cast<size_t>(k) * n_[1] + j) * n_[0] + i);
  };
  for (size_t t = 0; t < n; ++t) each_cell(t, [&](size_t c) { ++offsets_[c + 1]; });
  for (size_t c = 1; c < offsets_.size(); ++c) offsets_[c] += offsets_[c - 1];
  items_.resize(offsets_.back());
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (size_t t = 0; t < n; ++t) each_cell(t, [&](size_t c) { items_[fill[c]++] = static_cast<int>(t); });
}

bool TriangleGrid::Settle(const std::vector<Triangle>& triangles, const Kernel::Point_3& q, Kernel::Point_3* at,
                          int* hint) const {
  if (items_.empty()) return false;
  const Kernel kernel;
  const double hint_d2 = CGAL::squared_distance(q, *at);
  const double r = std::sqrt(hint_d2) * (1.0 + 1e-6) + slack_;
  const Eigen::Vector3d p(q.x(), q.y(), q.z());
  if (!(r <= 1.5 * cell_) || !p.allFinite()) return false;  // a cube over more than 27 cells; NaN
  std::array<int, 3> from{}, to{};
  int count = 1;
  for (int a = 0; a < 3; ++a) {
    from[a] = Cell(p[a] - r, a), to[a] = Cell(p[a] + r, a);
    count *= to[a] - from[a] + 1;
  }
  if (count > kMaxCells) return false;
  bool displaced = false;  // a triangle whose projection is not farther and another point
  int best = -1;
  Kernel::Point_3 best_point;
  double best_d2 = hint_d2, second_d2 = INFINITY;  // the closest other than the hint; the next
  for (int k = from[2]; k <= to[2]; ++k)
    for (int j = from[1]; j <= to[1]; ++j)
      for (int i = from[0]; i <= to[0]; ++i) {
        const size_t c = (static_cast<size_t>(k) * n_[1] + j) * n_[0] + i;
        for (int e = offsets_[c]; e < offsets_[c + 1]; ++e) {
          const int t = items_[e];
          if (t == *hint || t == best) continue;
          const auto& b = boxes_[t];
          if (b[0] > p.x() + r || b[3] < p.x() - r || b[1] > p.y() + r || b[4] < p.y() - r || b[2] > p.z() + r ||
              b[5] < p.z() - r)
            continue;
          const Kernel::Point_3 other = kernel.construct_projected_point_3_object()(triangles[t], q);
          if (kernel.compare_distance_3_object()(q, other, *at) == CGAL::LARGER || kernel.equal_3_object()(other, *at))
            continue;
          displaced = true;
          const double d2 = CGAL::squared_distance(q, other);
          if (best < 0 || d2 < best_d2) {
            second_d2 = std::min(second_d2, best < 0 ? hint_d2 : best_d2);
            best = t, best_point = other, best_d2 = d2;
          } else {
            second_d2 = std::min(second_d2, d2);
          }
        }
      }
  if (!displaced) return true;
  // One triangle closer than every other by a margin far above rounding: the tree search from
  // the hint visits it (its boxes are closer than any bound it holds before) and nothing can
  // displace it after. Ties, or near ties, go to the tree.
  if (!(best_d2 < (1.0 - 1e-9) * second_d2)) return false;
  *at = best_point, *hint = best;
  return true;
}

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
  tree_->grid.Build(tree_->triangles);
  for (const auto& [a, b] : g.boundary) tree_->segments.emplace_back(ToCgal(a), ToCgal(b));
  if (!tree_->segments.empty()) {
    tree_->boundary.insert(tree_->segments.cbegin(), tree_->segments.cend());
    tree_->boundary.build();
    tree_->boundary.accelerate_distance_queries();
  }
}

ClosestPointQuery::~ClosestPointQuery() = default;

SurfacePoint ClosestPointQuery::OnSurface(const Eigen::Vector3d& p, int hint) const {
  const Kernel::Point_3 q = ToCgal(p);
  Kernel::Point_3 at;
  SurfacePoint out;
  int settled = hint;
  if (hint >= 0 && hint < static_cast<int>(tree_->triangles.size()) &&
      tree_->grid.Settle(tree_->triangles, q, &(at = Kernel().construct_projected_point_3_object()(tree_->triangles[hint], q)),
                         &settled)) {
    out.element = settled;  // what the tree search from this hint returns (TriangleGrid)
  } else {
    const auto hit = Closest(tree_->tree, tree_->triangles, q, hint);
    at = hit.first;
    out.element = static_cast<int>(hit.second - tree_->triangles.cbegin());
  }
  out.point = Eigen::Vector3d(at.x(), at.y(), at.z());
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
