// ClosestPointQuery's hinted search (geometry/closest_point.h) against CGAL's own hinted tree
// search over the same triangles: the grid that settles a hint without the tree
// (closest_point.cc, TriangleGrid) must give the same triangle and the same point, to the bit,
// for points near the surface and far from it, hints near and far, and points on shared edges
// and vertices (where several triangles project to the same point).
#include <gtest/gtest.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <random>
#include <vector>

#include "geometry/closest_point.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

TEST(ClosestPoint, HintedAnswersAreCgalsToTheBit) {
  // A wavy 40 × 40 m roof of 2 × 40 × 40 triangles, with a crease along x = 12.
  const SurfaceModel s(testing::ToMesh(testing::GridSoup(40, [](double x, double y) {
    return 0.6 * std::sin(0.5 * x) * std::cos(0.4 * y) + 0.3 * std::abs(x - 12.0);
  })));
  const ClosestPointQuery query(s);
  std::vector<Triangle> triangles;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    const auto point = [&](int k) {
      const Eigen::Vector3d p = s.position(ids[k]);
      return Kernel::Point_3(p.x(), p.y(), p.z());
    };
    triangles.emplace_back(point(0), point(1), point(2));
  }
  Tree tree(triangles.cbegin(), triangles.cend());
  tree.accelerate_distance_queries();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d lo = s.bbox_min(), hi = s.bbox_max();
  int settled_near = 0, checked = 0;
  const auto check = [&](const Eigen::Vector3d& p, int hint) {
    const Kernel::Point_3 q(p.x(), p.y(), p.z());
    const auto expected = tree.closest_point_and_primitive(
        q, {Kernel().construct_projected_point_3_object()(triangles[hint], q), triangles.cbegin() + hint});
    const SurfacePoint got = query.OnSurface(p, hint);
    ASSERT_EQ(got.element, static_cast<int>(expected.second - triangles.cbegin())) << p.transpose() << " hint " << hint;
    ASSERT_EQ(got.point.x(), expected.first.x());
    ASSERT_EQ(got.point.y(), expected.first.y());
    ASSERT_EQ(got.point.z(), expected.first.z());
    ++checked;
    settled_near += got.element == hint;
  };
  for (int k = 0; k < 4000; ++k) {
    // A point near the surface (up to 0.3 m off it), asked with the answer for a point nearby
    // (a vertex sliding: mostly the same triangle, sometimes a neighbour) and with a far hint.
    const Eigen::Vector3d base(lo.x() + unit(random) * (hi.x() - lo.x()), lo.y() + unit(random) * (hi.y() - lo.y()), 0.0);
    const SurfacePoint on = query.OnSurface(base + Eigen::Vector3d(0.0, 0.0, hi.z()));
    const Eigen::Vector3d offset(0.2 * (unit(random) - 0.5), 0.2 * (unit(random) - 0.5), 0.6 * (unit(random) - 0.5));
    check(on.point + offset, on.element);
    check(on.point + 1e-9 * offset, on.element);
    check(on.point + offset, static_cast<int>(unit(random) * s.num_faces()));
  }
  for (int v = 0; v < s.num_vertices(); v += 7)  // on a vertex: every triangle round it projects there
    for (int f = 0; f < s.num_faces(); f += 211) check(s.position(v), f);
  for (int f = 0; f < s.num_faces(); f += 5) {  // on an edge's midpoint, hinted with its triangle
    const auto ids = s.face_vertices(f);
    check(0.5 * (s.position(ids[0]) + s.position(ids[1])), f);
  }
  check(Eigen::Vector3d(1e12, -3e15, 7.0), 17);  // far off the grid: the tree's answer, no overflow
  check(Eigen::Vector3d(20.0, 20.0, 1e3), 17);
  EXPECT_FALSE(std::isfinite(query.OnSurface(Eigen::Vector3d(NAN, 1.0, 1.0), 17).distance));  // no crash
  std::cout << checked << " queries, " << settled_near << " answered by their hint\n";
  EXPECT_GT(settled_near, checked / 4);  // the grid's path is taken, not only the tree's
}

}  // namespace
}  // namespace pqlayout
