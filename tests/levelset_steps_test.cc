// The level sets' step solvers (levelset.linear_solver): conjugate gradients preconditioned by
// the factor without the smoothness terms find the known minimum, and the key chooses them.
#include <gtest/gtest.h>

#include <ceres/ceres.h>

#include <cmath>
#include <string>
#include <vector>

#include "problems/levelset.h"
#include "problems/levelset_internal.h"
#include "tests/test_guidance.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::GeneratedMesh;
using testing::UniformGuidance;

// u_v = target (a test-only term): with it the minimum of spacing + smoothness + anchors is known.
struct AnchorResidual {
  double target;
  template <typename T>
  bool operator()(const T* u, T* r) const {
    r[0] = u[0] - target;
    return true;
  }
};

// The level-set solves' linear solver: conjugate gradients preconditioned by the factor
// without the smoothness terms (levelset_terms.cc, Solve). Every smoothness block is recorded,
// and the solve still lands on the known minimum: φ = x / h zeroes every term — the spacing
// (h|∇φ| = 1), the smoothness (a linear function has no jump in gradient) and the anchors
// that single it out among the minima of the other two — from a start 0.1 h off it.
TEST(LevelSets, SolveLeavesTheSmoothnessToConjugateGradientsAndFindsTheMinimum) {
  const SurfaceModel s(GeneratedMesh("plane", 12.0, 12.0, 0.0, 1.0));
  const levelset_internal::LevelSetGeometry geo = levelset_internal::Precompute(s);
  const auto edges = levelset_internal::InteriorEdges(s, geo);
  const double h = 3.0;
  std::vector<double> phi(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v)
    phi[v] = s.position(v).x() / h + 0.1 * std::sin(s.position(v).x()) * std::cos(0.7 * s.position(v).y());
  const levelset_internal::Chart chart{&phi, {}};
  levelset_internal::TermProblem terms(true);  // levelset.linear_solver = cg
  levelset_internal::AddSpacing(s, geo, h, 5.0, chart, {}, &terms);
  levelset_internal::AddSmoothness(edges, h, 0.01, chart, &terms);
  EXPECT_EQ(terms.smoothness.size(), edges.size());
  {  // with cholesky the same blocks, none recorded (nothing reads them)
    levelset_internal::TermProblem plain(false);
    levelset_internal::AddSmoothness(edges, h, 0.01, chart, &plain);
    EXPECT_EQ(plain.problem.NumResidualBlocks(), static_cast<int>(edges.size()));
    EXPECT_TRUE(plain.smoothness.empty());
  }
  for (int v = 0; v < s.num_vertices(); v += 3)
    terms.problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AnchorResidual, 1, 1>(
                                       new AnchorResidual{s.position(v).x() / h}),
                                   nullptr, &phi[v]);
  nlohmann::json summary;
  ASSERT_TRUE(levelset_internal::Solve("test", 100, &terms, &summary).ok());
  EXPECT_LT(summary["final_cost"].get<double>(), 1e-12);
  EXPECT_EQ(summary["linear_solver"], "CGNR");
  for (int v = 0; v < s.num_vertices(); ++v) EXPECT_NEAR(phi[v], s.position(v).x() / h, 1e-6) << "vertex " << v;
  // Without smoothness blocks the factor is the whole system: plain sparse Cholesky.
  levelset_internal::TermProblem anchors(true);
  anchors.problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AnchorResidual, 1, 1>(new AnchorResidual{1.0}),
                                   nullptr, &phi[0]);
  ASSERT_TRUE(levelset_internal::Solve("test", 5, &anchors, &summary).ok());
  EXPECT_EQ(summary["linear_solver"], "SPARSE_NORMAL_CHOLESKY");
  EXPECT_NEAR(phi[0], 1.0, 1e-6);
}

// levelset.linear_solver chooses each step's solver (report.json's ceres entries name it), and
// levelset.separate_solves whether φ and ψ are solved one by one before the joint solve (the
// paper's order) or the joint solve starts from the initial guess (default); the flat square's
// straight, even lines come out of each.
TEST(LevelSets, LinearSolverKeyChoosesTheStepsSolver) {
  const SurfaceModel s(GeneratedMesh("plane", 12.0, 12.0, 0.0, 0.6));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitX(); });
  EXPECT_EQ(LevelsetOptions().linear_solver, "cholesky");
  EXPECT_FALSE(LevelsetOptions().separate_solves);
  for (const std::string solver : {"cholesky", "cg"}) {
    for (const bool separate : {false, true}) {
      LevelsetOptions options;
      options.linear_solver = solver;
      options.separate_solves = separate;
      LevelSetSolution solution;
      ASSERT_TRUE(SolveLevelSets(s, g, options, 1.5, &solution).ok());
      EXPECT_EQ(solution.solver.contains("phi"), separate);
      EXPECT_EQ(solution.solver.contains("psi"), separate);
      for (const char* solve : {"phi", "psi", "joint"})
        if (solution.solver.contains(solve))
          EXPECT_EQ(solution.solver.at(solve).at("linear_solver"), solver == "cg" ? "CGNR" : "SPARSE_NORMAL_CHOLESKY")
              << solver << " " << solve;
      EXPECT_LE(solution.metrics.alignment_rms_deg, 0.1) << solver << separate;
      EXPECT_LE(solution.metrics.spacing_cv_phi, 1e-3) << solver << separate;
      EXPECT_GE(solution.metrics.min_crossing_angle_deg, 89.0) << solver << separate;
    }
  }
}

}  // namespace
}  // namespace pqlayout
