// The compliance gradient of the grid frame (adjoint, problems/grid_frame.h) against central
// finite differences, the closed-form member energy it differentiates, the joints it keeps,
// and every residual functor of the stiffen stage against finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "problems/grid_frame.h"
#include "problems/residuals/fairness_change_residual.h"
#include "problems/residuals/joint_length_residual.h"
#include "problems/residuals/planarity_budget_residual.h"
#include "problems/residuals/signed_planarity_residual.h"
#include "solver/framed_point_cost.h"
#include "tests/frame_grids.h"
#include "tests/gradient_check.h"

namespace pqlayout {
namespace {

using testing::MixedSupports;
using testing::QuadGrid;

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
  ExpectJacobiansMatchFiniteDifferences("planarity (signed)", SignedPlanarityResidual::Create(), {a, b, c, d});
  const std::vector<double> plane{0.1, 0.2, 0.97467943, 0.3};
  ExpectJacobiansMatchFiniteDifferences("planarity (budget)", PlanarityBudgetResidual::Create(1e6, 1.4, 1e-4, Eigen::Vector3d(0.5, -0.3, 0.2)), {plane, b});
  ExpectJacobiansMatchFiniteDifferences("fairness change",
                                        FairnessChangeResidual::Create(Eigen::Vector3d(0.1, -0.2, 0.05), 0.1, 3.0), {a, b, c});
  ExpectJacobiansMatchFiniteDifferences("joint length", JointLengthResidual::Create(0.5, 1e4, 3.0), {a, b});
  // The local-frame adapter: the planarity functor seen through a rotated, shifted frame.
  PointFrame frame;
  frame.origin = Eigen::Vector3d(1.0, 2.0, 3.0);
  frame.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  ExpectJacobiansMatchFiniteDifferences(
      "framed point", new FramedPointCost(PlanarityBudgetResidual::Create(1e6, 1.4, 0.0, Eigen::Vector3d(0.5, -0.3, 0.2)), {nullptr, &frame}), {plane, b});
}

// Keeping the start's joints (grid_frame.h) gives the same frame and compliance bit for bit.
TEST(ComplianceGradient, KeptJointsGiveTheSameFrame) {
  PolyMesh mesh = QuadGrid(4, 1.0, 0.3, 0.05, 7);
  const VertexHandle v(6), w(7);
  mesh.set_point(w, mesh.point(v) + OpenMesh::Vec3d(0.02, 0.01, 0.0));  // edge 6–7 shorter than the section depth
  const auto r = MixedSupports(mesh, 4.0);
  GridCompliance fresh, kept;
  ASSERT_TRUE(EvaluateGridCompliance(mesh, r, AnalysisOptions(), true, &fresh).ok());
  ASSERT_EQ(fresh.frame.joints, 1);
  std::vector<bool> joints;
  for (const auto e : mesh.edges()) {
    const auto he = mesh.halfedge_handle(e, 0);
    joints.push_back(fresh.frame.node_of[mesh.from_vertex_handle(he).idx()] == fresh.frame.node_of[mesh.to_vertex_handle(he).idx()]);
  }
  ASSERT_TRUE(EvaluateGridCompliance(mesh, r, AnalysisOptions(), true, &kept, nullptr, &joints).ok());
  EXPECT_EQ(kept.compliance, fresh.compliance);
  EXPECT_EQ(kept.frame.joints, 1);
  // Forced: no joints at all is a different frame (one member more).
  const std::vector<bool> none(joints.size(), false);
  GridCompliance forced;
  ASSERT_TRUE(EvaluateGridCompliance(mesh, r, AnalysisOptions(), false, &forced, nullptr, &none).ok());
  EXPECT_EQ(forced.frame.joints, 0);
  EXPECT_EQ(forced.frame.model.members.size(), kept.frame.model.members.size() + 1);
}

}  // namespace
}  // namespace pqlayout
