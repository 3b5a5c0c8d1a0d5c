// The roof corpus generators (geometry/roof_generators.h): each mesh against its own height
// field (heights at the vertices exact), its plan (area of the plan projection against the
// domain's exact area, minus the polygonal approximation of curved loops), its topology
// (boundary loops, Euler characteristic), triangle quality in space and orientation; the
// L's re-entrant corner is a vertex; and every one refuses a bad parameter naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/height_field.h"
#include "geometry/roof_generators.h"
#include "tests/generator_measures.h"

namespace pqlayout {
namespace {

struct Roof {
  friend void PrintTo(const Roof& roof, std::ostream* os) { *os << roof.name; }
  std::string name;
  Status (*build)(const GeneratorParams&, HeightField*);
  int loops;           // boundary loops (1 + holes)
  double plan_area;    // exact area of the plan domain for width 30, depth 24
  bool curved;         // a loop is a circle or an ellipse (its polygon is a little smaller)
};

constexpr double kW = 30.0, kD = 24.0;
constexpr double kPi = M_PI;
const double kHole = 0.12 * kD, kHole1 = 0.1 * kD, kHole2 = 0.08 * kD;
const Roof kRoofs[] = {
    {"dome_circular", DomeCircular, 1, kPi * 0.25 * kW * kW, true},
    {"saddle_elliptic", SaddleElliptic, 1, kPi * 0.25 * kW * kD, true},
    {"canopy", Canopy, 1, kW * kD, false},
    {"l_shape", LShape, 1, 0.75 * kW * kD, false},
    {"hole_offcentre", HoleOffCentre, 2, kW * kD - kPi * kHole * kHole, true},
    {"two_holes", TwoHoles, 3, kW * kD - kPi * (kHole1 * kHole1 + kHole2 * kHole2), true},
    {"wavy", Wavy, 1, kW * kD, false},
};

class RoofGenerator : public ::testing::TestWithParam<Roof> {
 protected:
  GeneratorParams Params() const {
    GeneratorParams params = pqlayout::Params(GetParam().name, 1.0);
    params.width = kW, params.depth = kD, params.rise = 4.0;
    return params;
  }
};

double PlanArea(const TriMesh& mesh) {
  double area = 0.0;
  for (FaceHandle f : mesh.faces()) {
    const Eigen::Vector3d a = Corner(mesh, f, 0), b = Corner(mesh, f, 1), c = Corner(mesh, f, 2);
    area += 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  }
  return area;
}

TEST_P(RoofGenerator, IsItsHeightFieldOverItsPlan) {
  const Roof& roof = GetParam();
  const TriMesh mesh = Generate(Params());
  HeightField field;
  ASSERT_TRUE(roof.build(Params(), &field).ok());
  EXPECT_LT(MaxHeightError(mesh, field.height), 1e-12);
  // A polygon with sides ≤ e inscribed in a circle of radius r misses at most e²/(8r) of
  // each unit of its perimeter (an outer loop's plan is that much smaller, a hole that much
  // larger): under 0.5 % here; straight plans are exact.
  const double area = PlanArea(mesh);
  EXPECT_NEAR(area, roof.plan_area, (roof.curved ? 5e-3 : 1e-9) * roof.plan_area);
  EXPECT_EQ(CountBoundaryLoops(mesh), roof.loops);
  EXPECT_EQ(EulerCharacteristic(mesh), 2 - roof.loops);  // a disc with loops − 1 holes
}

TEST_P(RoofGenerator, HasGoodTrianglesFacingUp) {
  const MeshMeasures m = Measure(Generate(Params()));
  EXPECT_GE(m.min_angle, 20.0 * kDegree) << m.min_angle / kDegree;
  EXPECT_LE(m.max_edge, 1.5);
  EXPECT_GT(m.min_normal_z, 0.0);
}

TEST_P(RoofGenerator, RefusesABadParameterNamingIt) {
  for (const std::string key : {"width", "depth", "rise"}) {
    GeneratorParams params = Params();
    (key == "width" ? params.width : key == "depth" ? params.depth : params.rise) = -1.0;
    TriMesh mesh;
    const Status status = GenerateSurface(params, &mesh);
    EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
    EXPECT_NE(status.message().find("surface." + key), std::string::npos) << status.message();
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, RoofGenerator, ::testing::ValuesIn(kRoofs),
                         [](const auto& info) { return info.param.name; });

TEST(LShape, KeepsTheReEntrantCorner) {
  GeneratorParams params = Params("l_shape", 1.0);
  params.width = kW, params.depth = kD, params.rise = 4.0;
  EXPECT_TRUE(HasVertexAt(Generate(params), 0.0, 0.0));
}

}  // namespace
}  // namespace pqlayout
