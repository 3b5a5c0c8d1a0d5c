// Stage stiffen: the compliance gradient (adjoint, problems/grid_frame.h) against central
// finite differences, and the optimiser's guarantees (problems/stiffen.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "problems/grid_frame.h"
#include "geometry/closest_point.h"
#include "geometry/planarity.h"
#include "problems/stiffen.h"
#include "problems/residuals/fairness_change_residual.h"
#include "problems/residuals/joint_length_residual.h"
#include "problems/residuals/planarity_budget_residual.h"
#include "problems/residuals/planarity_lagrangian_residual.h"
#include "solver/framed_point_cost.h"
#include "tests/gradient_check.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

// An n × n grid of quads on [0, n·a]², z = rise × bump, vertices jittered by `jitter` (m).
PolyMesh QuadGrid(int n, double a, double rise, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PolyMesh mesh;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = i * a, y = j * a, L = n * a;
      const double z = rise * std::sin(M_PI * x / L) * std::sin(M_PI * y / L);
      const bool inside = i > 0 && j > 0 && i < n && j < n;
      const double dx = inside ? jitter * u(rng) : 0.0, dy = inside ? jitter * u(rng) : 0.0, dz = jitter * u(rng);
      v.push_back(mesh.add_vertex({x + dx, y + dy, z + dz}));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int k = j * (n + 1) + i;
      mesh.add_face(std::vector<VertexHandle>{v[k], v[k + 1], v[k + n + 2], v[k + n + 1]});
    }
  return mesh;
}

// Boundary supports of every kind: x = 0 pinned, y = 0 clamped, x = max sliding, y = max free.
std::vector<Restraints> MixedSupports(const PolyMesh& mesh, double L) {
  std::vector<Restraints> r(mesh.n_vertices(), Restraints{});
  for (const auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    if (std::abs(p[1] - L) < 1e-9) continue;
    if (std::abs(p[0]) < 1e-9) r[v.idx()] = {true, true, true, false, false, false};
    else if (std::abs(p[1]) < 1e-9) r[v.idx()] = {true, true, true, true, true, true};
    else if (std::abs(p[0] - L) < 1e-9) r[v.idx()] = {false, false, true, false, false, false};
  }
  return r;
}

double Compliance(const PolyMesh& mesh, const std::vector<Restraints>& r, const AnalysisOptions& a) {
  GridCompliance c;
  EXPECT_TRUE(EvaluateGridCompliance(mesh, r, a, false, &c).ok());
  return c.compliance;
}

void ExpectGradientMatchesFiniteDifferences(const PolyMesh& start, const std::vector<Restraints>& r,
                                            const AnalysisOptions& a) {
  GridCompliance c;
  ASSERT_TRUE(EvaluateGridCompliance(start, r, a, true, &c).ok());
  double g_max = 0.0;
  for (const auto& g : c.gradient) g_max = std::max(g_max, g.cwiseAbs().maxCoeff());
  ASSERT_GT(g_max, 0.0);
  const double step = 1e-5;
  double worst = 0.0;
  for (const auto v : start.vertices())
    for (int k = 0; k < 3; ++k) {
      PolyMesh plus = start, minus = start;
      auto p = start.point(v);
      p[k] += step, plus.set_point(v, p);
      p[k] -= 2 * step, minus.set_point(v, p);
      const double fd = (Compliance(plus, r, a) - Compliance(minus, r, a)) / (2 * step);
      worst = std::max(worst, std::abs(fd - c.gradient[v.idx()][k]) / g_max);
    }
  EXPECT_LT(worst, 1e-6) << "largest |dC/dx − FD| / max |dC/dx|";
}

TEST(ComplianceGradient, MatchesFiniteDifferencesOnARandomGridWithEverySupportKind) {
  const PolyMesh mesh = QuadGrid(4, 1.0, 0.6, 0.15, 7);
  AnalysisOptions a;
  ExpectGradientMatchesFiniteDifferences(mesh, MixedSupports(mesh, 4.0), a);
}

TEST(ComplianceGradient, MatchesFiniteDifferencesWithAJointAndARectangularSection) {
  PolyMesh mesh = QuadGrid(4, 1.0, 0.6, 0.1, 11);
  // Vertex (1, 1) 6 cm from vertex (1, 2)... moved next to its neighbour (2, 1): a joint.
  const VertexHandle v(1 * 5 + 1), w(1 * 5 + 2);
  auto p = mesh.point(w);
  p[0] -= 0.05, p[1] += 0.02;
  mesh.set_point(v, p);
  AnalysisOptions a;
  a.section.shape = "rectangular_hollow";
  GridFrame frame;
  const auto r = MixedSupports(mesh, 4.0);
  BuildGridFrame(mesh, r, a, &frame);
  ASSERT_EQ(frame.joints, 1);
  ExpectGradientMatchesFiniteDifferences(mesh, r, a);
}

// A shallow 4 m × 4 m roof (rise `rise`) as reference and as a 4 × 4 quad grid on it, the
// whole boundary pinned.
struct ShallowRoof {
  explicit ShallowRoof(double rise)
      : reference(testing::ToMesh(testing::GridSoup(4, [rise](double x, double y) { return Height(rise, x, y); }))) {
    grid.mesh = QuadGrid(4, 1.0, 0.0, 0.0, 1);
    for (const auto v : grid.mesh.vertices()) {
      auto p = grid.mesh.point(v);
      p[2] = Height(rise, p[0], p[1]);
      grid.mesh.set_point(v, p);
      QuadMeshVertex origin;
      origin.on_boundary = grid.mesh.is_boundary(v);
      grid.origin.push_back(origin);
      restraints.push_back(origin.on_boundary ? Restraints{true, true, true, false, false, false} : Restraints{});
    }
  }
  static double Height(double rise, double x, double y) { return rise * std::sin(M_PI * x / 4) * std::sin(M_PI * y / 4); }
  SurfaceModel reference;
  ExtractedMesh grid;
  std::vector<Restraints> restraints;
};

TEST(Stiffen, ZeroToleranceLeavesTheMeshBitForBit) {
  ShallowRoof roof(0.3);
  const PolyMesh before = roof.grid.mesh;
  StiffenOptions options;
  options.tolerance = 0.0;
  StiffenReport report;
  ASSERT_TRUE(StiffenMesh(roof.reference, roof.restraints, AnalysisOptions(), options, 1e-3, 1.0, &roof.grid, &report).ok());
  for (const auto v : before.vertices())
    for (int k = 0; k < 3; ++k) EXPECT_EQ(before.point(v)[k], roof.grid.mesh.point(v)[k]);
  EXPECT_EQ(report.compliance_ratio, 1.0);
  EXPECT_EQ(report.iterations, 0);
}

// Known answer: a nearly flat grid under gravity is stiffer the more it arches, so the
// optimiser lifts its middle by (nearly) all the tolerance allows, and never more.
TEST(Stiffen, ANearlyFlatGridRisesByTheTolerance) {
  ShallowRoof roof(0.02);
  const PolyMesh before = roof.grid.mesh;
  StiffenOptions options;
  options.tolerance = 0.1;
  const double target = 0.05;  // generous: a 4 × 4 grid with a held boundary has little planar freedom
  StiffenReport report;
  ASSERT_TRUE(StiffenMesh(roof.reference, roof.restraints, AnalysisOptions(), options, target, 1.0, &roof.grid, &report).ok());
  const VertexHandle middle(2 * 5 + 2);
  const double rise = roof.grid.mesh.point(middle)[2] - ShallowRoof::Height(0.02, 2.0, 2.0);
  EXPECT_GT(rise, 0.08) << "the middle rises by most of the 0.1 m tolerance";
  EXPECT_LT(report.compliance_ratio, 0.5);
  // Hard limits, checked exactly: distance to the reference, planarity, boundary held.
  const ClosestPointQuery query(roof.reference);
  for (const auto v : roof.grid.mesh.vertices()) {
    EXPECT_LE(query.OnSurface(ToEigen(roof.grid.mesh.point(v))).distance, options.tolerance) << v.idx();
    if (roof.grid.origin[v.idx()].on_boundary) EXPECT_EQ(roof.grid.mesh.point(v), before.point(v)) << v.idx();
  }
  for (const auto f : roof.grid.mesh.faces()) {
    std::vector<Eigen::Vector3d> polygon;
    for (const auto v : roof.grid.mesh.fv_range(f)) polygon.push_back(ToEigen(roof.grid.mesh.point(v)));
    EXPECT_LE(PlanarityDelta(polygon), target) << "face " << f.idx();
  }
  EXPECT_LE(report.planarity_max, target);
  EXPECT_LE(report.closeness_max, options.tolerance);
}

// The closed-form member energy the gradient differentiates equals uᵀ K u of the element.
TEST(ComplianceGradient, ClosedFormMemberEnergyEqualsTheElementStiffness) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  const FrameSection s = FrameSection::RectangularHollow(0.06, 0.12, 0.005);
  FrameMaterial m;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d a(r(rng), r(rng), r(rng)), b = a + Eigen::Vector3d(2.0 + r(rng), r(rng), r(rng)),
                          up(r(rng), r(rng), 1.0);
    Eigen::Matrix<double, 12, 1> u;
    for (int k = 0; k < 12; ++k) u[k] = 1e-3 * r(rng);
    const double reference = u.dot(WorldBeamStiffness<double>(a, b, up, s, m) * u);
    EXPECT_NEAR(BeamEnergyTwice<double>(a, b, up, u, s, m), reference, 1e-10 * std::abs(reference)) << trial;
  }
}

// Every residual functor of the stiffen stage against finite differences.
TEST(StiffenResiduals, JacobiansMatchFiniteDifferences) {
  using testing::ExpectJacobiansMatchFiniteDifferences;
  const std::vector<double> a{0.1, 0.2, 0.05}, b{1.1, 0.1, 0.3}, c{1.2, 1.05, -0.1}, d{0.05, 0.9, 0.2};
  const double lambda = 0.3, rho = 1e4;
  ExpectJacobiansMatchFiniteDifferences("planarity (Lagrangian)", PlanarityLagrangianResidual::Create(&lambda, &rho, 1e-3),
                                        {a, b, c, d});
  const std::vector<double> plane{0.1, 0.2, 0.97467943, 0.3};
  ExpectJacobiansMatchFiniteDifferences("planarity (budget)", PlanarityBudgetResidual::Create(1e6, 1.4, 1e-4), {plane, b});
  ExpectJacobiansMatchFiniteDifferences("fairness change",
                                        FairnessChangeResidual::Create(Eigen::Vector3d(0.1, -0.2, 0.05), 0.1, 3.0), {a, b, c});
  ExpectJacobiansMatchFiniteDifferences("joint length", JointLengthResidual::Create(0.5, 1e4, 3.0), {a, b});
  // The local-frame adapter: the planarity functor seen through a rotated, shifted frame.
  PointFrame frame;
  frame.origin = Eigen::Vector3d(1.0, 2.0, 3.0);
  frame.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  ExpectJacobiansMatchFiniteDifferences(
      "framed point", new FramedPointCost(PlanarityBudgetResidual::Create(1e6, 1.4, 0.0), {nullptr, &frame}), {plane, b});
}

// The Lagrangian term is exactly (1/2ρ) max(0, λ + ρ g)² (up to −λ²/2ρ) with g = δ − δ_allowed.
TEST(StiffenResiduals, LagrangianTermIsThePowellHestenesRockafellarPenalty) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0.02), c(1, 1, 0), d(0, 1, 0.02);
  const double delta = QuadPlanarityDelta(a, b, c, d), lambda = 2.0, rho = 1e4, allowed = 1e-3;
  const PlanarityLagrangianResidual term(&lambda, &rho, allowed);
  double r = 0.0;
  term(a.data(), b.data(), c.data(), d.data(), &r);
  const double g = delta - allowed;
  EXPECT_NEAR(0.5 * r * r, std::pow(std::max(0.0, lambda + rho * g), 2) / (2 * rho), 1e-12);
  EXPECT_GT(delta, 0.01);
}

}  // namespace
}  // namespace pqlayout
