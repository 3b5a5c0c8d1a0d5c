// Micro-benchmarks of the pieces the stages are made of (issue 8): the per-face level-set
// residuals with autodiff against hand-written Jacobians (the smoothness one is in
// levelset_benchmark.cc), closest-point queries on the reference (CGAL AABB tree, used by
// planarisation at every evaluation), and quad extraction on references of growing size.
// Cotangent assembly and CHOLMOD factor/solve are in membrane_benchmark.cc.
#include <benchmark/benchmark.h>
#include <ceres/ceres.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "geometry/closest_point.h"
#include "geometry/quad_extraction.h"
#include "geometry/surface_generators.h"
#include "problems/residuals/alignment_residual.h"
#include "problems/residuals/spacing_residual.h"

namespace pqlayout {
namespace {

// Alignment r = s·⟨G u, d⟩ is linear in u: J = s·(Gᵀ d)ᵀ.
class AnalyticAlignment : public ceres::SizedCostFunction<1, 1, 1, 1> {
 public:
  AnalyticAlignment(const Eigen::Matrix3d& G, const Eigen::Vector3d& d, double scale) : j_(scale * G.transpose() * d) {}
  bool Evaluate(double const* const* u, double* residual, double** jacobians) const override {
    residual[0] = j_.dot(Eigen::Vector3d(u[0][0], u[1][0], u[2][0]));
    if (jacobians)
      for (int p = 0; p < 3; ++p)
        if (jacobians[p]) jacobians[p][0] = j_[p];
    return true;
  }

 private:
  Eigen::Vector3d j_;
};

// Spacing r = √A (h |G u| − 1): J = √A h (G u)ᵀ G / |G u|.
class AnalyticSpacing : public ceres::SizedCostFunction<1, 1, 1, 1> {
 public:
  AnalyticSpacing(const Eigen::Matrix3d& G, double area, double h) : G_(G), sqrt_area_(std::sqrt(area)), h_(h) {}
  bool Evaluate(double const* const* u, double* residual, double** jacobians) const override {
    const Eigen::Vector3d g = G_ * Eigen::Vector3d(u[0][0], u[1][0], u[2][0]);
    const double length = g.norm();
    residual[0] = sqrt_area_ * (h_ * length - 1.0);
    if (jacobians) {
      const Eigen::Vector3d j = length > 0.0 ? Eigen::Vector3d(sqrt_area_ * h_ * G_.transpose() * g / length)
                                             : Eigen::Vector3d::Zero();
      for (int p = 0; p < 3; ++p)
        if (jacobians[p]) jacobians[p][0] = j[p];
    }
    return true;
  }

 private:
  Eigen::Matrix3d G_;
  double sqrt_area_, h_;
};

void EvaluateLoop(benchmark::State& state, const ceres::CostFunction& cost) {
  double u[3] = {0.1, -0.3, 0.7}, r[1], J[3];
  const double* blocks[3] = {&u[0], &u[1], &u[2]};
  double* jacobians[3] = {&J[0], &J[1], &J[2]};
  for (auto _ : state) {
    cost.Evaluate(blocks, r, jacobians);
    benchmark::DoNotOptimize(J);
  }
}

const Eigen::Matrix3d kG = (Eigen::Matrix3d() << 0.3, -0.7, 0.4, 1.1, 0.2, -1.3, 0.05, 0.1, -0.15).finished();
const Eigen::Vector3d kD = Eigen::Vector3d(0.6, 0.8, 0.0);

void BM_AlignmentJacobianAutodiff(benchmark::State& state) {
  std::unique_ptr<ceres::CostFunction> cost(AlignmentResidual::Create(kG, kD, 0.8, 0.9, 3.0));
  EvaluateLoop(state, *cost);
}
void BM_AlignmentJacobianAnalytic(benchmark::State& state) {
  AnalyticAlignment cost(kG, kD, std::sqrt(0.8 * 0.9) * 3.0);
  EvaluateLoop(state, cost);
}
void BM_SpacingJacobianAutodiff(benchmark::State& state) {
  std::unique_ptr<ceres::CostFunction> cost(SpacingResidual::Create(kG, 0.9, 3.0));
  EvaluateLoop(state, *cost);
}
void BM_SpacingJacobianAnalytic(benchmark::State& state) {
  AnalyticSpacing cost(kG, 0.9, 3.0);
  EvaluateLoop(state, cost);
}
BENCHMARK(BM_AlignmentJacobianAutodiff);
BENCHMARK(BM_AlignmentJacobianAnalytic);
BENCHMARK(BM_SpacingJacobianAutodiff);
BENCHMARK(BM_SpacingJacobianAnalytic);

const SurfaceModel& GreatCourt(double edge_length) {
  static std::map<double, std::unique_ptr<SurfaceModel>> cache;
  auto& slot = cache[edge_length];
  if (!slot) {
    GeneratorParams p;
    p.name = "great_court";
    p.edge_length = edge_length;
    TriMesh mesh;
    if (!GenerateSurface(p, &mesh).ok()) std::abort();
    slot = std::make_unique<SurfaceModel>(std::move(mesh));
  }
  return *slot;
}

// Closest point on the Great Court reference of random points within 0.5 m of it; the arg
// is the reference edge length in cm (150: 12k triangles, 50: 112k).
void BM_ClosestPointOnSurface(benchmark::State& state) {
  const SurfaceModel& s = GreatCourt(state.range(0) / 100.0);
  const ClosestPointQuery query(s);
  std::mt19937 random(7);
  std::uniform_int_distribution<int> vertex(0, s.num_vertices() - 1);
  std::uniform_real_distribution<double> offset(-0.5, 0.5);
  std::vector<Eigen::Vector3d> points(4096);
  for (auto& p : points) p = s.position(vertex(random)) + Eigen::Vector3d(offset(random), offset(random), offset(random));
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(query.OnSurface(points[i++ % points.size()]).point);
  state.counters["triangles"] = s.num_faces();
}
BENCHMARK(BM_ClosestPointOnSurface)->Arg(150)->Arg(50);

// Quad extraction of a rotated 3 m grid (φ, ψ = plan coordinates rotated by 0.4 rad, over h)
// on the Great Court reference; the arg is the reference edge length in cm.
void BM_ExtractQuadMesh(benchmark::State& state) {
  const SurfaceModel& s = GreatCourt(state.range(0) / 100.0);
  std::vector<double> phi, psi;
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d p = s.position(v);
    phi.push_back((std::cos(0.4) * p.x() + std::sin(0.4) * p.y()) / 3.0 + 0.37);
    psi.push_back((-std::sin(0.4) * p.x() + std::cos(0.4) * p.y()) / 3.0 + 0.21);
  }
  int faces = 0;
  for (auto _ : state) {
    ExtractedMesh out;
    if (!ExtractQuadMesh(s, phi, psi, 30.0, 0.6, &out).ok()) std::abort();
    faces = static_cast<int>(out.mesh.n_faces());
  }
  state.counters["triangles"] = s.num_faces();
  state.counters["quad_faces"] = faces;
}
BENCHMARK(BM_ExtractQuadMesh)->Arg(150)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pqlayout
