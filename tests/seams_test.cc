// Seams (geometry/seams.h): routing and cutting the surface open.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "geometry/seams.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {
using testing::ClosestInterior;
using testing::GeneratedMesh;

TEST(Seams, AnnulusIsCutIntoADiscAlongOnePath) {
  const SurfaceModel s(GeneratedMesh("annulus", 20.0, 8.0, 0.0, 1.0));
  ASSERT_EQ(s.boundary_loops().size(), 2u);
  // Weight 1 except a corridor along +x: the seam must take the corridor.
  std::vector<double> weight(s.num_faces(), 1.0);
  for (int f = 0; f < s.num_faces(); ++f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const int v : s.face_vertices(f)) c += s.position(v) / 3.0;
    if (c.x() > 0 && std::abs(c.y()) < 1.5) weight[f] = 0.0;
  }
  const auto paths = RouteSeams(s, weight, {});
  ASSERT_EQ(paths.size(), 1u);
  for (const int v : paths[0]) EXPECT_GT(s.position(v).x(), 0.0);
  EXPECT_NE(s.boundary_loop_of(paths[0].front()), s.boundary_loop_of(paths[0].back()));
  std::unique_ptr<SeamCut> cut;
  ASSERT_TRUE(SeamCut::Build(s, paths, &cut).ok());
  const SurfaceModel& c = cut->cut();
  // A disc: one boundary loop, χ = 1; every path vertex doubled, nothing else.
  EXPECT_EQ(c.boundary_loops().size(), 1u);
  EXPECT_EQ(c.num_vertices(), s.num_vertices() + static_cast<int>(paths[0].size()));
  EXPECT_EQ(c.num_vertices() - static_cast<int>(c.mesh().n_edges()) + c.num_faces(), 1);
  EXPECT_EQ(c.num_faces(), s.num_faces());
  for (int f = 0; f < s.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(cut->original_vertex(c.face_vertices(f)[k]), s.face_vertices(f)[k]);
  EXPECT_EQ(cut->seam_edges().size(), paths[0].size() - 1);
  EXPECT_EQ(cut->copy_pairs().size(), paths[0].size());
  for (const auto& pair : cut->copy_pairs()) EXPECT_NE(pair.minus, pair.plus);
  for (const auto& e : cut->seam_edges()) {
    EXPECT_TRUE(c.mesh().is_boundary(EdgeHandle(e.cut_edge_minus)));
    EXPECT_TRUE(cut->is_seam_edge(e.cut_edge_plus));
    EXPECT_NE(e.cut_edge_minus, e.cut_edge_plus);
  }
  // Round trip of values.
  std::vector<double> values(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v) values[v] = v;
  EXPECT_EQ(cut->ToOriginal(cut->ToCut(values)), values);
}

TEST(Seams, TipSeamEndsInsideWithOneCopy) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 1.0));
  const int tip = ClosestInterior(s, 2.0, 1.0);
  const auto paths = RouteSeams(s, std::vector<double>(s.num_faces(), 1.0), {tip});
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_EQ(paths[0].front(), tip);
  EXPECT_TRUE(s.is_boundary(paths[0].back()));
  // Straight to the nearest boundary point (10 − |(2, 1)| ≈ 7.76 m) within mesh zigzag.
  double length = 0.0;
  for (size_t k = 0; k + 1 < paths[0].size(); ++k)
    length += (s.position(paths[0][k + 1]) - s.position(paths[0][k])).norm();
  EXPECT_LT(length, 1.15 * (10.0 - std::hypot(2.0, 1.0)));
  std::unique_ptr<SeamCut> cut;
  ASSERT_TRUE(SeamCut::Build(s, paths, &cut).ok());
  // The tip keeps one copy, every other path vertex gets two.
  EXPECT_EQ(cut->cut().num_vertices(), s.num_vertices() + static_cast<int>(paths[0].size()) - 1);
  int tips = 0;
  for (const auto& pair : cut->copy_pairs()) tips += pair.minus == pair.plus;
  EXPECT_EQ(tips, 1);
  EXPECT_EQ(cut->cut().boundary_loops().size(), 1u);
}

TEST(Seams, BadPathsAreRefused) {
  const SurfaceModel s(GeneratedMesh("disk", 20.0, 0.0, 0.0, 1.0));
  std::unique_ptr<SeamCut> cut;
  const int a = ClosestInterior(s, 0.0, 0.0), b = ClosestInterior(s, 5.0, 0.0);
  EXPECT_FALSE(SeamCut::Build(s, {{a, b}}, &cut).ok());        // not adjacent, not on the boundary
  EXPECT_FALSE(SeamCut::Build(s, {{a}}, &cut).ok());           // too short
  const auto paths = RouteSeams(s, std::vector<double>(s.num_faces(), 1.0), {a});
  EXPECT_FALSE(SeamCut::Build(s, {paths[0], paths[0]}, &cut).ok());  // shared vertices
}

}  // namespace
}  // namespace pqlayout
