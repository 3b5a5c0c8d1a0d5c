// Guidance fields: the Green–Lagrange tensor, principal strain directions on the flat disk
// (radial, ε_max = ½|∇v_z|²), curvature directions on a cylinder and a sphere, weights, the
// CSV source, line-field singularities and persistent minima.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <random>

#include "geometry/differential_operators.h"
#include "geometry/line_field_singularities.h"
#include "geometry/principal_directions.h"
#include "geometry/scalar_field_extrema.h"
#include "geometry/surface_generators.h"
#include "problems/guidance.h"
#include "problems/membrane.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

TriMesh Generate(const std::string& name, double width, double depth, double rise, double edge) {
  return testing::GeneratedMesh(name, width, depth, rise, edge);
}

double AngleBetweenLinesDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * 180.0 / M_PI;
}

TEST(GreenLagrange, KernelSymmetryAndLengthDiscrepancy) {
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d n = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
    const Eigen::Vector3d g = P * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    const Eigen::Matrix3d eps = GreenLagrangeStrain(n, g);
    EXPECT_NEAR((eps - eps.transpose()).norm(), 0.0, 1e-15);
    EXPECT_NEAR((eps * n).norm(), 0.0, 1e-14);
    // tᵀ ε t = ½ (|DT t|² − |t|²) for tangent t, DT t = t + e_z (g·t): the membrane strain.
    const Eigen::Vector3d t = P * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    const Eigen::Vector3d mapped = t + Eigen::Vector3d::UnitZ() * g.dot(t);
    EXPECT_NEAR(t.dot(eps * t), 0.5 * (mapped.squaredNorm() - t.squaredNorm()), 1e-13);
  }
}

TEST(StrainGuidance, FlatDiskIsRadialWithHalfSquaredGradient) {
  const SurfaceModel s(Generate("disk", 2.0, 0.0, 0.0, 0.05));
  VertexConditions supports(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v)
    if (s.is_boundary(v)) supports[v] = BoundaryCondition::kFixed;
  MembraneOptions membrane;
  membrane.stiffness = 100.0;
  MembraneSolution solution;
  ASSERT_TRUE(SolveMembrane(s, supports, membrane, 1350.0, &solution).ok());
  GuidanceField g;
  ASSERT_TRUE(ComputeStrainGuidance(s, solution.v_z, GuidanceOptions(), &g).ok());
  double angle_sum = 0.0, worst_strain_error = 0.0;
  int counted = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    const Eigen::Vector3d centre = (s.position(ids[0]) + s.position(ids[1]) + s.position(ids[2])) / 3.0;
    if (centre.norm() <= 0.2) continue;
    angle_sum += AngleBetweenLinesDeg(g.direction[f], Eigen::Vector3d(centre.x(), centre.y(), 0.0));
    ++counted;
    const double half_squared_gradient = 0.5 * FaceGradient(s, f, solution.v_z).squaredNorm();
    worst_strain_error = std::max(worst_strain_error, std::abs(g.major[f] - half_squared_gradient) / half_squared_gradient);
    // Paper's orientation, with the flat-face fallback: towards increasing v_z (outwards).
    EXPECT_GT(g.direction[f].dot(centre), 0.0);
  }
  EXPECT_LE(angle_sum / counted, 1.0) << "mean angle error, degrees";
  EXPECT_LE(worst_strain_error, 0.02);
  std::cout << "disk: mean radial angle error " << angle_sum / counted << "°, worst |ε_max − ½|∇v|²| / ½|∇v|² "
            << worst_strain_error << "\n";
}

// A plane tilted along x (z = x / 2) moved vertically by v_z: ε = sym(a ⊗ ∇v) + ½ ∇v ∇vᵀ with
// a = P e_z along the slope, so a ∇v across the slope gives nearly pure shear, ε_min ≈ −ε_max.
struct TiltedPlane {
  std::unique_ptr<SurfaceModel> surface;
  GuidanceField paper, weak;  // guidance.shear_switch = paper, weak
};
TiltedPlane TiltedPlaneStrain(const std::function<double(double, double)>& v) {
  TriMesh mesh = Generate("plane", 10.0, 10.0, 0.0, 0.5);
  for (const auto vh : mesh.vertices()) {
    auto p = mesh.point(vh);
    p[2] = 0.5 * p[0];
    mesh.set_point(vh, p);
  }
  TiltedPlane plane{std::make_unique<SurfaceModel>(mesh), {}, {}};
  const SurfaceModel& s = *plane.surface;
  std::vector<double> v_z(s.num_vertices());
  for (int i = 0; i < s.num_vertices(); ++i) v_z[i] = v(s.position(i).x(), s.position(i).y());
  GuidanceOptions options;
  options.shear_switch = "paper";
  EXPECT_TRUE(ComputeStrainGuidance(s, v_z, options, &plane.paper).ok());
  options.shear_switch = "weak";
  EXPECT_TRUE(ComputeStrainGuidance(s, v_z, options, &plane.weak).ok());
  return plane;
}

// Uniform pure shear: the paper's weight is 1 everywhere (|ε_max| is the same on every face);
// e_max is as ambiguous as it gets (|ε_min| = |ε_max| − ½|∇v|²), so the weak weight is 0.
TEST(StrainGuidance, PureShearHasNoWeightUnlessAsThePaperSays) {
  const TiltedPlane plane = TiltedPlaneStrain([](double, double y) { return 0.01 * y; });
  const SurfaceModel* s = plane.surface.get();
  const GuidanceField &paper = plane.paper, &weak = plane.weak;
  for (int f = 0; f < s->num_faces(); ++f) {
    ASSERT_LT(paper.major[f] * paper.minor[f], 0.0) << "face " << f;
    EXPECT_NEAR(std::abs(paper.minor[f]) / std::abs(paper.major[f]), 1.0, 0.03);
    EXPECT_NEAR(paper.weight[f], 1.0, 1e-12);
    EXPECT_EQ(weak.weight[f], 0.0);
    EXPECT_EQ(weak.direction[f], paper.direction[f]);  // only the weight differs
    EXPECT_EQ(weak.magnitude[f], paper.magnitude[f]);
  }
}

// Shear whose trace changes sign across the roof (v = 0.01 y + 0.0005 x²): e_max, the
// eigenvector of largest modulus, swaps by 90° where ε_max = −ε_min. Every face next to the
// swap has no weak weight, while the paper's weight there is above 0.5; away from it (|ε_max| −
// |ε_min| ≥ 0.3 of the largest |ε_max|) the two weights agree.
TEST(StrainGuidance, WeightVanishesWhereTheLargestModulusSwapsDirection) {
  const TiltedPlane plane = TiltedPlaneStrain([](double x, double y) { return 0.01 * y + 0.0005 * x * x; });
  const SurfaceModel* s = plane.surface.get();
  const GuidanceField &paper = plane.paper, &weak = plane.weak;
  int swaps = 0, agree = 0;
  for (int f = 0; f < s->num_faces(); ++f) {
    EXPECT_LE(weak.weight[f], paper.weight[f] + 1e-15);
    for (const auto n : s->mesh().ff_range(FaceHandle(f))) {
      if (AngleBetweenLinesDeg(paper.direction[f], paper.direction[n.idx()]) < 60.0) continue;
      ++swaps;
      EXPECT_EQ(weak.weight[f], 0.0) << "face " << f;
      EXPECT_GT(paper.weight[f], 0.5) << "face " << f;
    }
    if (std::abs(paper.major[f]) - std::abs(paper.minor[f]) >= 0.3 * paper.scale) {
      ++agree;
      EXPECT_NEAR(weak.weight[f], paper.weight[f], 1e-12);
    }
  }
  EXPECT_GT(swaps, 10);  // the swap line crosses the roof
  EXPECT_GT(agree, s->num_faces() / 10);
}

TEST(CurvatureGuidance, CylinderFollowsTheCurvedDirection) {
  // A barrel vault curves in x and is straight along y.
  const SurfaceModel s(Generate("barrel", 10.0, 12.0, 3.0, 0.4));
  GuidanceField g;
  ASSERT_TRUE(ComputeCurvatureGuidance(s, GuidanceOptions(), &g).ok());
  double worst = 0.0, sum = 0.0;
  int high_weight = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d& n = s.face_normal(f);
    const Eigen::Vector3d around = Eigen::Vector3d::UnitY().cross(n);  // the circle's tangent
    const double angle = AngleBetweenLinesDeg(g.direction[f], around);
    worst = std::max(worst, angle);
    sum += angle;
    high_weight += g.weight[f] == 1.0;
  }
  std::cout << "cylinder: mean angle " << sum / s.num_faces() << "°, worst " << worst << "°\n";
  EXPECT_LE(sum / s.num_faces(), 1.0);  // measured 0.25°
  EXPECT_LE(worst, 5.0);                // measured 3.6°, on faces at the boundary
  EXPECT_GT(high_weight, 0.95 * s.num_faces());
}

// The signed ordering κ1 ≥ κ2 (orientation ±1) against the paper's largest modulus (0).
TEST(PrincipalDirections, OrientationChoosesTheSignedOrTheLargestEigenvalue) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d t = Eigen::Vector3d(1.0, -2.0, 0.0).asDiagonal();
  EXPECT_DOUBLE_EQ(DecomposeOnTangentPlane(t, n).major, -2.0);
  EXPECT_DOUBLE_EQ(DecomposeOnTangentPlane(t, n, 1).major, 1.0);
  EXPECT_DOUBLE_EQ(DecomposeOnTangentPlane(t, n, 1).minor, -2.0);
  EXPECT_DOUBLE_EQ(DecomposeOnTangentPlane(t, n, -1).major, -2.0);
  EXPECT_NEAR(std::abs(DecomposeOnTangentPlane(t, n, 1).major_direction.x()), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(DecomposeOnTangentPlane(t, n, -1).major_direction.y()), 1.0, 1e-12);
}

// A hyperbolic paraboloid z ∝ x y on a square has no umbilic: its curvature lines are the two
// diagonals' families everywhere. With the largest-|κ| ordering the field turned by 90° along
// the axes, where κ1 = −κ2, and the guidance had 70 spurious ±½ singularities.
TEST(CurvatureGuidance, HyparIsDiagonalWithoutSingularities) {
  const SurfaceModel s(Generate("hypar", 24.0, 24.0, 4.0, 0.6));
  GuidanceField g;
  ASSERT_TRUE(ComputeCurvatureGuidance(s, GuidanceOptions(), &g).ok());
  EXPECT_TRUE(FindLineFieldSingularities(s, g.direction).empty());
  double worst = 0.0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d d(g.direction[f].x(), g.direction[f].y(), 0.0);
    const double from_diagonal = std::min(AngleBetweenLinesDeg(d, Eigen::Vector3d(1, 1, 0)),
                                          AngleBetweenLinesDeg(d, Eigen::Vector3d(1, -1, 0)));
    worst = std::max(worst, from_diagonal);
  }
  std::cout << "hypar: worst angle to a diagonal " << worst << "°\n";
  EXPECT_LE(worst, 10.0);
}

TEST(CurvatureGuidance, SphereHasNoPreferredDirection) {
  // A spherical cap of radius 10 over the disk of radius 6.
  TriMesh mesh = Generate("disk", 12.0, 0.0, 0.0, 0.3);
  for (const auto v : mesh.vertices()) {
    auto p = mesh.point(v);
    p[2] = std::sqrt(100.0 - p[0] * p[0] - p[1] * p[1]);
    mesh.set_point(v, p);
  }
  const SurfaceModel s(std::move(mesh));
  GuidanceField g;
  ASSERT_TRUE(ComputeCurvatureGuidance(s, GuidanceOptions(), &g).ok());
  EXPECT_NEAR(g.scale, 0.2, 0.02);  // max |κ1| + |κ2| = 2/R
  double worst_weight = 0.0;
  for (const double w : g.weight) worst_weight = std::max(worst_weight, w);
  EXPECT_LE(worst_weight, 0.05);
}

TEST(Guidance, WeightsRampFromThreshold) {
  const std::vector<double> magnitude{0.0, 0.1, 0.2, 0.25, 0.3, 0.9, 1.0};
  const auto w = AlignmentWeights(magnitude, 1.0, 0.2, 0.1);
  const std::vector<double> expected{0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0};
  for (size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(w[i], expected[i], 1e-12) << i;
  const auto step = AlignmentWeights(magnitude, 2.0, 0.2, 0.0);  // relative 0, .05, .1, .125, .15, .45, .5
  EXPECT_EQ(step, (std::vector<double>{0, 0, 0, 0, 0, 1, 1}));
}

// The curvature fallback blends two line fields by their doubled angles (guidance.h): on a
// flat mesh, per face, source d_s = e₁ with weight w_s and curvature direction at angle α with
// weight w_κ, β = 0.5: z = w_s + (1 − w_s)·β·w_κ·e^{2iα}; direction at ½ arg z from d_s.
TEST(Guidance, CurvatureFallbackBlendsLineFieldsByDoubledAngles) {
  const SurfaceModel s(Generate("disk", 2.0, 0.0, 0.0, 0.5));
  ASSERT_GE(s.num_faces(), 6);
  struct Case {
    double w_s, alpha_deg, w_k;
    double expected_deg, expected_weight;
  };
  const double beta = 0.5;
  const std::vector<Case> cases{
      {1.0, 70.0, 1.0, 0.0, 1.0},                      // a strong source stays as it is
      {0.0, 70.0, 1.0, 70.0, 0.5},                     // no source: the curvature line at β·w_κ
      {0.5, 90.0, 1.0, 0.0, 0.25},                     // crossed lines cancel: 0.5 − 0.25
      {0.5, 45.0, 1.0, 0.5 * std::atan2(0.25, 0.5) * 180.0 / M_PI, std::hypot(0.5, 0.25)},
      {0.5, -45.0, 0.4, -0.5 * std::atan2(0.1, 0.5) * 180.0 / M_PI, std::hypot(0.5, 0.1)},
      {0.25, 180.0, 1.0, 0.0, 0.25 + 0.375}};        // a line has no sign: α = 180° is α = 0°
  GuidanceField source, curvature;
  for (int f = 0; f < s.num_faces(); ++f) {
    const Case& c = cases[f % cases.size()];
    const Eigen::Vector3d n = s.face_normal(f), e1 = n.unitOrthogonal(), e2 = n.cross(e1);
    const double a = c.alpha_deg * M_PI / 180.0;
    source.direction.push_back(f % 2 == 0 ? e1 : Eigen::Vector3d(-e1));  // the source's orientation is kept
    source.weight.push_back(c.w_s);
    curvature.direction.push_back(std::cos(a) * e1 + std::sin(a) * e2);
    curvature.weight.push_back(c.w_k);
  }
  GuidanceField blended = source;
  AddCurvatureFallback(s, curvature, beta, &blended);
  for (int f = 0; f < s.num_faces(); ++f) {
    const Case& c = cases[f % cases.size()];
    const Eigen::Vector3d n = s.face_normal(f);
    const Eigen::Vector3d d_s = source.direction[f], e2 = n.cross(d_s);
    const double sign = c.w_s > 0.0 ? 1.0 : (f % 2 == 0 ? 1.0 : -1.0);  // no source: d_κ as given
    const double angle = std::atan2(blended.direction[f].dot(e2), blended.direction[f].dot(d_s)) * 180.0 / M_PI;
    const double expected = c.w_s > 0.0 ? c.expected_deg : std::atan2(sign * std::sin(c.alpha_deg * M_PI / 180.0), sign * std::cos(c.alpha_deg * M_PI / 180.0)) * 180.0 / M_PI;
    EXPECT_NEAR(angle, expected, 1e-9) << "face " << f;
    EXPECT_NEAR(blended.direction[f].norm(), 1.0, 1e-12);
    EXPECT_NEAR(blended.direction[f].dot(n), 0.0, 1e-12);
    EXPECT_NEAR(blended.weight[f], c.expected_weight, 1e-12) << "face " << f;
    EXPECT_EQ(blended.source_weight[f], source.weight[f]);
    EXPECT_EQ(blended.source_direction[f], source.direction[f]);
  }
  GuidanceField none = source;  // β = 0: the source alone where it has a direction
  AddCurvatureFallback(s, curvature, 0.0, &none);
  for (int f = 0; f < s.num_faces(); ++f)
    if (source.weight[f] > 0.0) EXPECT_NEAR(none.weight[f], source.weight[f], 1e-15);
}

TEST(Guidance, FileSourceProjectsOntoFacesAndNamesErrors) {
  const auto dir = testing::TempDir();
  const SurfaceModel s(testing::ToMesh(testing::GridSoup(2, [](double x, double) { return x; })));
  std::string csv = "id,dx,dy,dz\n";
  for (int f = 0; f < s.num_faces(); ++f) csv += std::to_string(f) + ",0,0,1\n";  // e_z onto the plane z = x
  GuidanceOptions options;
  options.file = testing::WriteFile(dir, "g.csv", csv);
  GuidanceField g;
  ASSERT_TRUE(ReadGuidanceFile(s, options, &g).ok());
  for (int f = 0; f < s.num_faces(); ++f) {
    EXPECT_NEAR((g.direction[f] - Eigen::Vector3d(1, 0, 1).normalized()).norm(), 0.0, 1e-12);
    EXPECT_EQ(g.weight[f], 1.0);
  }
  options.file = testing::WriteFile(dir, "short.csv", "0,1,0,0\n");
  EXPECT_NE(ReadGuidanceFile(s, options, &g).message().find("no direction for face 1"), std::string::npos);
  options.file = testing::WriteFile(dir, "bad.csv", "0,1,0,0\n99,1,0,0\n");
  EXPECT_NE(ReadGuidanceFile(s, options, &g).message().find("bad.csv:2: face id"), std::string::npos);
  options.file = dir + "/none.csv";
  EXPECT_EQ(ReadGuidanceFile(s, options, &g).code(), StatusCode::kInvalidInput);
}

std::vector<Eigen::Vector3d> FieldOnFaces(const SurfaceModel& s, Eigen::Vector3d (*field)(const Eigen::Vector3d&)) {
  std::vector<Eigen::Vector3d> d(s.num_faces());
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    d[f] = field((s.position(ids[0]) + s.position(ids[1]) + s.position(ids[2])) / 3.0);
  }
  return d;
}

TEST(LineFieldSingularities, IndicesOfSourceSaddleAndWedge) {
  const SurfaceModel s(Generate("disk", 2.0, 0.0, 0.0, 0.1));
  auto single = [&](Eigen::Vector3d (*field)(const Eigen::Vector3d&)) {
    const auto found = FindLineFieldSingularities(s, FieldOnFaces(s, field));
    double total = 0.0;
    for (const auto& x : found) total += x.index;
    EXPECT_EQ(found.size(), 1u);
    if (!found.empty()) EXPECT_LT(found[0].position.norm(), 0.15);
    return total;
  };
  EXPECT_EQ(single([](const Eigen::Vector3d& p) { return Eigen::Vector3d(p.x(), p.y(), 0); }), 1.0);   // source
  EXPECT_EQ(single([](const Eigen::Vector3d& p) { return Eigen::Vector3d(p.x(), -p.y(), 0); }), -1.0); // saddle
  // Line field at half the polar angle: the ½ singularity of a wedge.
  EXPECT_EQ(single([](const Eigen::Vector3d& p) {
              const double half = 0.5 * std::atan2(p.y(), p.x());
              return Eigen::Vector3d(std::cos(half), std::sin(half), 0);
            }),
            0.5);
  // A constant field has none, whatever sign each face carries.
  std::vector<Eigen::Vector3d> constant(s.num_faces(), Eigen::Vector3d::UnitX());
  for (int f = 0; f < s.num_faces(); f += 3) constant[f] = -constant[f];
  EXPECT_TRUE(FindLineFieldSingularities(s, constant).empty());
}

TEST(PersistentMinima, TwoWellsWithNoiseCountTwice) {
  const SurfaceModel s(Generate("plane", 10.0, 4.0, 0.0, 0.2));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  std::vector<double> values(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d p = s.position(v);
    values[v] = -std::exp(-((p.x() - 2.5) * (p.x() - 2.5) + p.y() * p.y())) -
                0.8 * std::exp(-((p.x() + 2.5) * (p.x() + 2.5) + p.y() * p.y())) + noise(rng);
  }
  const auto minima = PersistentMinima(s, values, 0.02);
  ASSERT_EQ(minima.size(), 2u);
  EXPECT_NEAR(s.position(minima[0].vertex).x(), 2.5, 0.3);
  EXPECT_NEAR(s.position(minima[1].vertex).x(), -2.5, 0.3);
  EXPECT_NEAR(minima[1].persistence, 0.8, 0.05);
}

// A synthetic field on the flat 10 × 10 m plane: direction(x, y) and weight(x, y) at each face's
// centroid.
GuidanceField FlatField(const SurfaceModel& s, const std::function<Eigen::Vector3d(double, double)>& direction,
                        const std::function<double(double, double)>& weight) {
  GuidanceField g;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    const Eigen::Vector3d c = (s.position(ids[0]) + s.position(ids[1]) + s.position(ids[2])) / 3.0;
    g.direction.push_back(direction(c.x(), c.y()).normalized());
    g.major.push_back(2.0);
    g.minor.push_back(1.0);
    g.magnitude.push_back(weight(c.x(), c.y()));
    g.weight.push_back(weight(c.x(), c.y()));
  }
  return g;
}

// The major curvature direction swaps by 90° along the line x = 0 (radial inside a ring
// ridge's parallel, circles outside): combed, every face follows one family, and the swapped
// faces carry the other principal values.
TEST(CurvatureGuidance, CombingJoinsTheNetAcrossALineWhereTheFamiliesSwap) {
  const SurfaceModel s(Generate("plane", 10.0, 10.0, 0.0, 0.5));
  GuidanceField g = FlatField(
      s, [](double x, double) { return x < 0.0 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY(); },
      [](double x, double) { return std::min(1.0, std::abs(x) / 2.0); });
  const GuidanceField before = g;
  const int swapped = CombCurvatureNet(s, 1.0, &g);
  int along_x = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    along_x += std::abs(g.direction[f].x()) > 0.999;
    EXPECT_NEAR(std::abs(g.direction[f].dot(before.direction[f])), g.major[f] == before.major[f] ? 1.0 : 0.0, 1e-12);
    EXPECT_EQ(g.weight[f], before.weight[f]);
  }
  EXPECT_TRUE(along_x == 0 || along_x == s.num_faces()) << along_x << " of " << s.num_faces();
  EXPECT_GT(swapped, s.num_faces() / 3);
  EXPECT_LT(swapped, 2 * s.num_faces() / 3);
}

// Where the major direction is continuous — a ±½ singularity (d turns by half the polar angle),
// a constant field — combing changes nothing. At the singularity's core (r < 0.5 m) the
// directions are noise, as a shape operator's are at an umbilic: there faces would flip, but
// they are parts smaller than min_area and take their surroundings' family.
TEST(CurvatureGuidance, CombingLeavesAContinuousNetAlone) {
  const SurfaceModel s(Generate("plane", 10.0, 10.0, 0.0, 0.5));
  for (const double index : {0.5, -0.5}) {
    const auto direction = [&](double x, double y) {
      const double r = std::hypot(x - 0.2, y - 0.3);
      const double t = r < 0.5 ? 1e4 * (x * x + 3.0 * y) : index * std::atan2(y - 0.3, x - 0.2);
      return Eigen::Vector3d(std::cos(t), std::sin(t), 0.0);
    };
    const auto weight = [](double x, double y) { return std::min(1.0, std::hypot(x - 0.2, y - 0.3) / 3.0); };
    GuidanceField merged = FlatField(s, direction, weight), raw = merged;
    EXPECT_EQ(CombCurvatureNet(s, 1.0, &merged), 0) << "index " << index;
    EXPECT_GT(CombCurvatureNet(s, 0.0, &raw), 0) << "index " << index;  // the core's faces, unmerged
  }
  GuidanceField constant = FlatField(
      s, [](double, double) { return Eigen::Vector3d(1.0, 2.0, 0.0); }, [](double, double) { return 0.7; });
  EXPECT_EQ(CombCurvatureNet(s, 1.0, &constant), 0);
}

}  // namespace
}  // namespace pqlayout
