// SurfaceModel's cached quantities against hand-computed values, and boundary loops.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/surface_model.h"
#include "problems/boundary_conditions.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

// A 4x4 grid of unit squares with a 2x2 hole in the middle (an annulus-like domain).
TriMesh GridWithHole() {
  PolygonSoup soup = testing::FlatGridSoup(4);
  std::vector<std::vector<int>> kept;
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const int cell = static_cast<int>(f) / 2, i = cell % 4, j = cell / 4;
    if (i >= 1 && i <= 2 && j >= 1 && j <= 2) continue;
    kept.push_back(soup.faces[f]);
  }
  soup.faces = kept;
  return testing::ToMesh(soup);
}

// After FreezeFields the fields named there can be filled and read, and a new one is refused:
// the figures read the reference on another thread while later stages fill its fields, and
// creating a property would change the mesh's property list under them.
TEST(SurfaceModel, FrozenFieldsAreFilledAndNoNewOneIsCreated) {
  SurfaceModel s(testing::ToMesh(testing::FlatGridSoup(2)));
  s.FreezeFields({"v_z", "phi"});
  auto v_z = s.VertexField<double>("v_z");
  v_z[VertexHandle(3)] = 2.5;
  EXPECT_EQ(s.VertexFieldValues("v_z")[3], 2.5);
  EXPECT_EQ(s.VertexFieldValues("phi")[3], 0.0);
  EXPECT_DEATH(s.VertexField<double>("psi"), "field 'psi' created after SurfaceModel::FreezeFields");
  EXPECT_DEATH(s.FaceField<int>("colour"), "field 'colour' created after SurfaceModel::FreezeFields");
  EXPECT_DEATH(s.VertexField<int>("v_z"), "field 'v_z' created after");  // the same name, another type
}

TEST(SurfaceModel, AreasNormalsAndLumpedVertexAreas) {
  // z = x: every triangle is a unit-square half tilted by 45°, area ½·√2.
  const SurfaceModel s(testing::ToMesh(testing::GridSoup(3, [](double x, double) { return x; })));
  EXPECT_EQ(s.num_faces(), 18);
  EXPECT_EQ(s.num_vertices(), 16);
  for (int f = 0; f < s.num_faces(); ++f) {
    EXPECT_NEAR(s.face_area(f), 0.5 * std::sqrt(2.0), 1e-14);
    EXPECT_NEAR((s.face_normal(f) - Eigen::Vector3d(-1, 0, 1).normalized()).norm(), 0.0, 1e-14);
  }
  EXPECT_NEAR(s.total_area(), 9.0 * std::sqrt(2.0), 1e-12);
  double lumped = 0.0;
  for (int v = 0; v < s.num_vertices(); ++v) lumped += s.vertex_area(v);
  EXPECT_NEAR(lumped, s.total_area(), 1e-12);
  // Corner (0,0) touches 2 triangles (the grid splits along the main diagonal).
  EXPECT_NEAR(s.vertex_area(0), 2.0 * 0.5 * std::sqrt(2.0) / 3.0, 1e-14);
}

TEST(SurfaceModel, SingleBoundaryLoopWithFourCorners) {
  const SurfaceModel s(testing::ToMesh(testing::FlatGridSoup(3)));
  ASSERT_EQ(s.boundary_loops().size(), 1u);
  EXPECT_TRUE(s.boundary_loops()[0].is_outer);
  EXPECT_EQ(s.boundary_loops()[0].vertices.size(), 12u);
  EXPECT_NEAR(s.boundary_loops()[0].length, 12.0, 1e-14);
  EXPECT_NEAR(s.boundary_loops()[0].vector_area.norm(), 9.0, 1e-12);
  EXPECT_EQ(s.num_boundary_vertices(), 12);
  auto corners = s.BoundaryCorners(30.0 * M_PI / 180.0);
  std::sort(corners.begin(), corners.end());
  EXPECT_EQ(corners, (std::vector<int>{0, 3, 12, 15}));
  EXPECT_FALSE(s.is_boundary(5));
  EXPECT_EQ(s.boundary_loop_of(5), -1);
}

TEST(SurfaceModel, OuterLoopIsTheLargestAndComesFirst) {
  const SurfaceModel s(GridWithHole());
  ASSERT_EQ(s.boundary_loops().size(), 2u);
  EXPECT_TRUE(s.boundary_loops()[0].is_outer);
  EXPECT_FALSE(s.boundary_loops()[1].is_outer);
  EXPECT_NEAR(s.boundary_loops()[0].length, 16.0, 1e-14);
  EXPECT_NEAR(s.boundary_loops()[1].length, 8.0, 1e-14);
  EXPECT_EQ(s.num_vertices(), 24);        // the hole's centre (2, 2) is used by no face
  EXPECT_EQ(s.boundary_loop_of(11), 1);   // (1, 2) lies on the hole
  EXPECT_EQ(s.boundary_loop_of(5), 0);    // (0, 1) lies on the outer boundary
}

TEST(SurfaceModel, NamedFieldsAreSharedByName) {
  SurfaceModel s(testing::ToMesh(testing::FlatGridSoup(2)));
  auto a = s.VertexField<double>("v_z");
  a[VertexHandle(3)] = 1.5;
  auto b = s.VertexField<double>("v_z");
  EXPECT_EQ(b[VertexHandle(3)], 1.5);
}

BoundaryRule Rule(BoundarySelector::Kind kind, BoundaryCondition c) {
  BoundaryRule r;
  r.select.kind = kind;
  r.condition = c;
  return r;
}

TEST(BoundaryConditions, RulesApplyInOrderOverTheDefault) {
  const SurfaceModel s(GridWithHole());
  BoundaryOptions options;
  options.default_condition = BoundaryCondition::kFree;
  options.rules.push_back(Rule(BoundarySelector::Kind::kInner, BoundaryCondition::kFixed));
  BoundaryRule box = Rule(BoundarySelector::Kind::kBox, BoundaryCondition::kSliding);
  box.select.box_min = Eigen::Vector3d(-1, -1, -1);
  box.select.box_max = Eigen::Vector3d(4.5, 0.5, 1);  // the bottom row y = 0
  options.rules.push_back(box);
  options.rules.push_back(Rule(BoundarySelector::Kind::kCorners, BoundaryCondition::kClamped));
  VertexConditions c;
  ASSERT_TRUE(ResolveBoundaryConditions(options, s, 30.0, &c).ok());
  auto at = [&](int i, int j) { return c[j * 5 + i]; };
  // Vertex ids below 12 are unchanged by dropping the hole's centre vertex (2, 2).
  ASSERT_TRUE(at(1, 1).has_value());
  EXPECT_EQ(*at(1, 1), BoundaryCondition::kClamped);    // inner loop, but also a corner of it
  EXPECT_EQ(*at(2, 1), BoundaryCondition::kFixed);      // inner loop
  EXPECT_EQ(*at(2, 0), BoundaryCondition::kSliding);    // bottom row
  EXPECT_EQ(*at(0, 0), BoundaryCondition::kClamped);    // outer corner
  EXPECT_EQ(*at(0, 2), BoundaryCondition::kFree);       // default
  int interior_with_condition = 0;
  for (int v = 0; v < s.num_vertices(); ++v) interior_with_condition += !s.is_boundary(v) && c[v].has_value();
  EXPECT_EQ(interior_with_condition, 0);
}

TEST(BoundaryConditions, BadRulesAreRefusedNamingTheRule) {
  const SurfaceModel s(testing::ToMesh(testing::FlatGridSoup(2)));
  BoundaryOptions options;
  options.rules.push_back(Rule(BoundarySelector::Kind::kInner, BoundaryCondition::kFree));
  VertexConditions c;
  Status st = ResolveBoundaryConditions(options, s, 30.0, &c);
  EXPECT_EQ(st.code(), StatusCode::kInvalidInput);
  EXPECT_NE(st.message().find("boundary.rules[0]: selects inner loops"), std::string::npos) << st.message();

  options.rules = {Rule(BoundarySelector::Kind::kIds, BoundaryCondition::kFree)};
  options.rules[0].select.ids = {4};  // the centre of a 2x2 grid
  st = ResolveBoundaryConditions(options, s, 30.0, &c);
  EXPECT_NE(st.message().find("vertex 4 is not a boundary vertex"), std::string::npos) << st.message();

  options.rules = {Rule(BoundarySelector::Kind::kBox, BoundaryCondition::kFree)};
  options.rules[0].select.box_min = Eigen::Vector3d(10, 10, 10);
  options.rules[0].select.box_max = Eigen::Vector3d(11, 11, 11);
  st = ResolveBoundaryConditions(options, s, 30.0, &c);
  EXPECT_NE(st.message().find("selects no boundary vertex"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace pqlayout
