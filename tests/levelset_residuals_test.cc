// Every level-set residual functor: autodiff Jacobians against finite differences
// (ceres::GradientChecker) at seeded random points, plus known zeros and invariances.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "geometry/differential_operators.h"
#include "problems/residuals/alignment_residual.h"
#include "problems/residuals/conjugacy_residual.h"
#include "problems/residuals/crossing_barrier_residual.h"
#include "problems/residuals/smoothness_residual.h"
#include "problems/residuals/spacing_residual.h"
#include "problems/residuals/transversality_residual.h"
#include "solver/affine_mapped_cost.h"
#include "tests/gradient_check.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

std::mt19937 rng(20261122);
double Uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

// A random, reasonably shaped triangle in 3D and its P1 basis gradients.
struct Face {
  Eigen::Matrix3d G;
  Eigen::Vector3d n;
  double area;
};
Face RandomFace() {
  PolygonSoup soup;
  soup.points = {{Uniform(-1, 0), Uniform(-1, 0), Uniform(-0.3, 0.3)},
                 {Uniform(1, 2), Uniform(-0.5, 0.5), Uniform(-0.3, 0.3)},
                 {Uniform(-0.5, 0.5), Uniform(1, 2), Uniform(-0.3, 0.3)}};
  soup.faces = {{0, 1, 2}};
  const SurfaceModel s(testing::ToMesh(soup));
  const auto g = FaceBasisGradients(s, 0);
  Face f;
  f.G << g[0], g[1], g[2];
  f.n = s.face_normal(0);
  f.area = s.face_area(0);
  return f;
}
Eigen::Vector3d RandomTangent(const Eigen::Vector3d& n) {
  const Eigen::Vector3d v(Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1));
  return (v - n * n.dot(v)).normalized();
}
Eigen::Matrix3d RandomShapeOperator(const Eigen::Vector3d& n) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Random();
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  return P * (A + A.transpose()) * P * 0.1;
}

using testing::ExpectJacobiansMatchFiniteDifferences;

std::vector<double> RandomValues(int n) {
  std::vector<double> v(n);
  for (double& x : v) x = Uniform(-2, 2);
  return v;
}

TEST(LevelsetResiduals, GradientCheckAtRandomPoints) {
  for (int trial = 0; trial < 25; ++trial) {
    const Face f = RandomFace(), g = RandomFace();
    const double h = Uniform(0.5, 3.0);
    ExpectJacobiansMatchFiniteDifferences(
        "AlignmentResidual", AlignmentResidual::Create(f.G, RandomTangent(f.n), Uniform(0, 1), f.area, h), RandomValues(3));
    ExpectJacobiansMatchFiniteDifferences("SpacingResidual", SpacingResidual::Create(f.G, f.area, h), RandomValues(3));
    ExpectJacobiansMatchFiniteDifferences("SmoothnessResidual", SmoothnessResidual::Create(f.G, g.G, (f.area + g.area) / 3, Uniform(0.3, 1.0), h),
                                          RandomValues(4));
    ExpectJacobiansMatchFiniteDifferences(
        "ConjugacyResidual", ConjugacyResidual::Create(f.G, f.n, RandomShapeOperator(f.n), 0.01, f.area), RandomValues(6));
    // Transversality: probe only where the hinge is smooth (|s − sin θ_min| not tiny).
    std::vector<double> values;
    double sine = 0.0;
    do {
      values = RandomValues(6);
      const Eigen::Vector3d gphi = f.G * Eigen::Vector3d(values[0], values[1], values[2]);
      const Eigen::Vector3d gpsi = f.G * Eigen::Vector3d(values[3], values[4], values[5]);
      sine = f.n.dot(gphi.cross(gpsi)) / std::max(gphi.norm() * gpsi.norm(), 1.0 / (h * h));
      // Also away from the kink of max(|∇φ||∇ψ|, 1/h²).
    } while (std::abs(sine - std::sin(0.5)) < 0.05 ||
             std::abs(h * h * (f.G * Eigen::Vector3d(values[0], values[1], values[2])).norm() *
                          (f.G * Eigen::Vector3d(values[3], values[4], values[5])).norm() - 1.0) < 0.05);
    ExpectJacobiansMatchFiniteDifferences("TransversalityResidual", TransversalityResidual::Create(f.G, f.n, 0.5, f.area, h), values);
    // The crossing barrier, with its floor 0.1–0.3 below s (in its smooth part, s < sin θ_min,
    // which the loop above keeps away from; above sin θ_min it is zero, which the check also
    // compares).
    ExpectJacobiansMatchFiniteDifferences("CrossingBarrierResidual",
                                          CrossingBarrierResidual::Create(f.G, f.n, 0.5, sine - Uniform(0.1, 0.3), f.area, h),
                                          values);
  }
}

// φ, ψ of a face such that their gradients are the given tangent vectors: solve G u = ∇u
// in the least-squares sense (exact for tangent targets: adding a constant is the null space).
Eigen::Vector3d ValuesWithGradient(const Face& f, const Eigen::Vector3d& gradient) {
  return f.G.colPivHouseholderQr().solve(gradient);
}

template <typename Functor>
double Evaluate(const ceres::CostFunction* cost, const std::vector<double>& values) {
  std::vector<const double*> blocks;
  for (const double& v : values) blocks.push_back(&v);
  double r[3] = {0, 0, 0};
  EXPECT_TRUE(cost->Evaluate(blocks.data(), r, nullptr));
  delete cost;
  return Eigen::Vector3d(r[0], r[1], r[2]).norm();
}

TEST(LevelsetResiduals, KnownZerosAndValues) {
  const Face f = RandomFace();
  const Eigen::Vector3d d = RandomTangent(f.n), across = f.n.cross(d);
  const double h = 2.0;
  // Level lines along d: ∇φ = across / h.
  const Eigen::Vector3d phi = ValuesWithGradient(f, across / h);
  const std::vector<double> phi_values{phi[0], phi[1], phi[2]};
  EXPECT_NEAR(Evaluate<AlignmentResidual>(AlignmentResidual::Create(f.G, d, 1.0, f.area, h), phi_values), 0.0, 1e-12);
  EXPECT_NEAR(Evaluate<SpacingResidual>(SpacingResidual::Create(f.G, f.area, h), phi_values), 0.0, 1e-12);
  // Level lines across d at unit sine: alignment r = √A.
  const Eigen::Vector3d crossing = ValuesWithGradient(f, d / h);
  EXPECT_NEAR(Evaluate<AlignmentResidual>(AlignmentResidual::Create(f.G, d, 1.0, f.area, h),
                                          {crossing[0], crossing[1], crossing[2]}),
              std::sqrt(f.area), 1e-12);
  // Spacing 2h instead of h: r = √A (½ − 1).
  EXPECT_NEAR(Evaluate<SpacingResidual>(SpacingResidual::Create(f.G, f.area, h), {phi[0] / 2, phi[1] / 2, phi[2] / 2}),
              0.5 * std::sqrt(f.area), 1e-12);
  // A linear function has no gradient jump across an edge of two coplanar faces.
  EXPECT_NEAR(Evaluate<SmoothnessResidual>(SmoothnessResidual::Create(f.G, f.G, f.area, 0.5, h),
                                           {phi[0], phi[1], phi[2], phi[2]}),
              0.0, 1e-12);
}

// Across a seam the plus side reads u₊ = s·u₋ + a through AffineMappedCost: residuals are
// those of the inner functor at the mapped values, Jacobians chained by s (GradientChecker),
// and a linear φ continued through a seam (s = −1, a = 3) has no smoothness jump.
TEST(LevelsetResiduals, AffineMappedCostIsTheInnerCostAtMappedValues) {
  for (int trial = 0; trial < 10; ++trial) {
    const Face f = RandomFace(), g = RandomFace();
    const double h = Uniform(0.5, 3.0);
    std::vector<double> scale(6), offset(6);
    for (int k = 0; k < 6; ++k) scale[k] = (trial + k) % 2 ? 1.0 : -1.0, offset[k] = std::round(Uniform(-4, 4));
    const std::vector<double> x = RandomValues(6);
    std::vector<double> mapped(6);
    for (int k = 0; k < 6; ++k) mapped[k] = scale[k] * x[k] + offset[k];
    const Eigen::Matrix3d S = RandomShapeOperator(f.n);
    const auto conjugacy = [&] { return ConjugacyResidual::Create(f.G, f.n, S, 0.01, f.area); };
    const double inner = Evaluate<ConjugacyResidual>(conjugacy(), mapped);
    EXPECT_NEAR(Evaluate<ConjugacyResidual>(new AffineMappedCost(conjugacy(), scale, offset), x), inner, 1e-12);
    ExpectJacobiansMatchFiniteDifferences(
        "AffineMappedCost(SmoothnessResidual)",
        new AffineMappedCost(SmoothnessResidual::Create(f.G, g.G, (f.area + g.area) / 3, 0.5, h),
                             {scale[0], scale[1], scale[2], scale[3]}, {offset[0], offset[1], offset[2], offset[3]}),
        RandomValues(4));
  }
  // One flat face seen from both sides of a seam: f holds φ, g (the same triangle) holds
  // −φ + 3 at its third vertex; read back through the map s·(u − a) the jump vanishes, and
  // without the map it does not.
  const Face f = RandomFace();
  const Eigen::Vector3d phi = ValuesWithGradient(f, RandomTangent(f.n));
  const double plus_l = -phi[2] + 3.0;
  EXPECT_NEAR(Evaluate<SmoothnessResidual>(new AffineMappedCost(SmoothnessResidual::Create(f.G, f.G, f.area, 0.5, 2.0),
                                                                {1, 1, 1, -1}, {0, 0, 0, 3}),
                                           {phi[0], phi[1], phi[2], plus_l}),
              0.0, 1e-9);
  EXPECT_GT(Evaluate<SmoothnessResidual>(SmoothnessResidual::Create(f.G, f.G, f.area, 0.5, 2.0),
                                         {phi[0], phi[1], phi[2], plus_l}),
            0.1);
}

TEST(LevelsetResiduals, ConjugacyVanishesOnPrincipalDirectionsAndIsScaleFree) {
  const Face f = RandomFace();
  const Eigen::Vector3d e1 = RandomTangent(f.n), e2 = f.n.cross(e1);
  const Eigen::Matrix3d S = 0.3 * e1 * e1.transpose() - 0.1 * e2 * e2.transpose();  // principal frame (e1, e2)
  // Level lines along e1 and e2: gradients n × ... rotated by 90°.
  const Eigen::Vector3d phi = ValuesWithGradient(f, e2), psi = ValuesWithGradient(f, -e1);
  auto conjugacy = [&](double sphi, double spsi, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    return Evaluate<ConjugacyResidual>(ConjugacyResidual::Create(f.G, f.n, S, 0.0, f.area),
                                       {sphi * p[0], sphi * p[1], sphi * p[2], spsi * q[0], spsi * q[1], spsi * q[2]});
  };
  EXPECT_NEAR(conjugacy(1, 1, phi, psi), 0.0, 1e-12);
  // Asymptotic-free oblique pair: not conjugate; the value does not change when φ, ψ scale.
  const Eigen::Vector3d tilted = ValuesWithGradient(f, (e2 + 0.5 * e1).normalized());
  const double r = conjugacy(1, 1, tilted, psi);
  EXPECT_GT(r, 1e-3);
  EXPECT_NEAR(conjugacy(3.5, 0.2, tilted, psi), r, 1e-12);
}

TEST(LevelsetResiduals, TransversalityPenalisesShallowCrossingsAndFoldOvers) {
  const Face f = RandomFace();
  const Eigen::Vector3d e1 = RandomTangent(f.n), e2 = f.n.cross(e1);
  const Eigen::Vector3d phi = ValuesWithGradient(f, e1);
  auto r = [&](const Eigen::Vector3d& psi_gradient) {
    const Eigen::Vector3d psi = ValuesWithGradient(f, psi_gradient);
    return Evaluate<TransversalityResidual>(TransversalityResidual::Create(f.G, f.n, M_PI / 6, f.area, 1.0),
                                            {phi[0], phi[1], phi[2], psi[0], psi[1], psi[2]});
  };
  EXPECT_NEAR(r(e2), 0.0, 1e-12);                                       // 90°, positive orientation
  EXPECT_NEAR(r(std::cos(0.2) * e1 + std::sin(0.2) * e2), std::sqrt(f.area) * (0.5 - std::sin(0.2)), 1e-12);
  EXPECT_NEAR(r(-e2), std::sqrt(f.area) * 1.5, 1e-12);                  // folded over: s = −1
  EXPECT_NEAR(r(Eigen::Vector3d::Zero()), std::sqrt(f.area) * 0.5, 1e-12); // collapsed ψ: penalised too
  EXPECT_NEAR(r(2.0 * e2), 0.0, 1e-12);                                  // denser ψ lines at 90°
  // Denser ψ lines at a shallow angle are penalised by their angle, not their density.
  EXPECT_NEAR(r(3.0 * (std::cos(0.2) * e1 + std::sin(0.2) * e2)), std::sqrt(f.area) * (0.5 - std::sin(0.2)), 1e-12);
  EXPECT_NEAR(r(0.5 * e2), std::sqrt(f.area) * 0.0, 1e-12);              // sparser at 90°: area ½ ≥ ½
}

TEST(LevelsetResiduals, CrossingBarrierGrowsWithoutBoundTowardsItsFloorAndRefusesBelow) {
  const Face f = RandomFace();
  const Eigen::Vector3d e1 = RandomTangent(f.n), e2 = f.n.cross(e1);
  const Eigen::Vector3d phi = ValuesWithGradient(f, e1);
  const double floor = std::sin(0.1);  // about 5.7°
  const auto evaluate = [&](double angle, double* r) {
    const Eigen::Vector3d psi = ValuesWithGradient(f, std::cos(angle) * e1 + std::sin(angle) * e2);
    const std::vector<double> values{phi[0], phi[1], phi[2], psi[0], psi[1], psi[2]};
    std::vector<const double*> blocks;
    for (const double& v : values) blocks.push_back(&v);
    std::unique_ptr<ceres::CostFunction> cost(CrossingBarrierResidual::Create(f.G, f.n, M_PI / 6, floor, f.area, 1.0));
    return cost->Evaluate(blocks.data(), r, nullptr);
  };
  double r = -1.0;
  ASSERT_TRUE(evaluate(M_PI / 2, &r));  // 90°: nothing to pay
  EXPECT_NEAR(r, 0.0, 1e-12);
  ASSERT_TRUE(evaluate(M_PI / 6 + 1e-9, &r));  // at θ_min: zero, continuously
  EXPECT_NEAR(r, 0.0, 1e-8);
  ASSERT_TRUE(evaluate(0.2, &r));  // (sin θ_min − s) / (s − t), times √A
  EXPECT_NEAR(r, std::sqrt(f.area) * (0.5 - std::sin(0.2)) / (std::sin(0.2) - floor), 1e-12);
  ASSERT_TRUE(evaluate(0.1 + 1e-6, &r));  // a hair above the floor: enormous
  EXPECT_GT(r, 1e5 * std::sqrt(f.area));
  EXPECT_FALSE(evaluate(0.1 - 1e-6, &r));  // at or below the floor (a fold-over too): refused,
  EXPECT_FALSE(evaluate(-0.3, &r));        // so Ceres rejects the step that would get there
}

}  // namespace
}  // namespace pqlayout
