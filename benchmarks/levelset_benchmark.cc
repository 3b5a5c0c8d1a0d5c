// Level-set stage: the hottest residual (smoothness: 3 residuals × 4 parameters per interior
// edge, the most numerous block) with autodiff against a hand-written analytic Jacobian,
// and the whole stage on the Great Court at the reference resolution.
#include <benchmark/benchmark.h>
#include <ceres/ceres.h>

#include "geometry/surface_generators.h"
#include "problems/levelset.h"
#include "problems/membrane.h"
#include "problems/residuals/smoothness_residual.h"

namespace pqlayout {
namespace {

// The smoothness residual with its Jacobian written by hand (it is linear in u:
// r = scale · (Gf·[u_i u_j u_k] − Gg·[u_i u_j u_l]), so J is constant).
class AnalyticSmoothness : public ceres::SizedCostFunction<3, 1, 1, 1, 1> {
 public:
  AnalyticSmoothness(const Eigen::Matrix3d& Gf, const Eigen::Matrix3d& Gg, double scale) {
    J_ << Gf.col(0) - Gg.col(0), Gf.col(1) - Gg.col(1), Gf.col(2), -Gg.col(2);
    J_ *= scale;
  }
  bool Evaluate(double const* const* u, double* residual, double** jacobians) const override {
    Eigen::Map<Eigen::Vector3d> r(residual);
    r = J_ * Eigen::Vector4d(u[0][0], u[1][0], u[2][0], u[3][0]);
    if (jacobians)
      for (int p = 0; p < 4; ++p)
        if (jacobians[p]) {
          Eigen::Map<Eigen::Vector3d> column(jacobians[p]);
          column = J_.col(p);
        }
    return true;
  }

 private:
  Eigen::Matrix<double, 3, 4> J_;
};

template <bool kAnalytic>
void BM_SmoothnessJacobian(benchmark::State& state) {
  const Eigen::Matrix3d Gf = Eigen::Matrix3d::Random(), Gg = Eigen::Matrix3d::Random();
  std::unique_ptr<ceres::CostFunction> cost(
      kAnalytic ? static_cast<ceres::CostFunction*>(new AnalyticSmoothness(Gf, Gg, 0.7))
                : SmoothnessResidual::Create(Gf, Gg, 0.49, 1.0, 1.0));
  double u[4] = {0.1, -0.3, 0.7, 1.1}, r[3], J[4][3];
  const double* blocks[4] = {&u[0], &u[1], &u[2], &u[3]};
  double* jacobians[4] = {J[0], J[1], J[2], J[3]};
  for (auto _ : state) {
    cost->Evaluate(blocks, r, jacobians);
    benchmark::DoNotOptimize(J);
  }
}
BENCHMARK_TEMPLATE(BM_SmoothnessJacobian, false)->Name("BM_SmoothnessJacobian/autodiff");
BENCHMARK_TEMPLATE(BM_SmoothnessJacobian, true)->Name("BM_SmoothnessJacobian/analytic");

// The level-set stage on the Great Court (paper's setting); argument: edge length in cm.
void BM_LevelsetStageGreatCourt(benchmark::State& state) {
  GeneratorParams params;
  params.name = "great_court";
  params.edge_length = state.range(0) / 100.0;
  TriMesh mesh;
  if (!GenerateSurface(params, &mesh).ok()) return state.SkipWithError("surface");
  const SurfaceModel surface(std::move(mesh));
  VertexConditions supports(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v)
    if (surface.is_boundary(v)) supports[v] = BoundaryCondition::kFixed;
  MembraneSolution membrane;
  GuidanceField guidance;
  if (!SolveMembrane(surface, supports, MembraneOptions(), 1350.0, &membrane).ok() ||
      !ComputeStrainGuidance(surface, membrane.v_z, GuidanceOptions(), &guidance).ok())
    return state.SkipWithError("membrane/guidance");
  LevelSetSolution solution;
  for (auto _ : state)
    if (!SolveLevelSets(surface, guidance, LevelsetOptions(), 3.0, &solution).ok()) state.SkipWithError("levelset");
  state.counters["triangles"] = surface.num_faces();
  state.counters["alignment_deg"] = solution.metrics.alignment_rms_deg;
  state.counters["foldovers"] = solution.metrics.foldovers;
}
BENCHMARK(BM_LevelsetStageGreatCourt)->Arg(150)->Arg(75)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace pqlayout
