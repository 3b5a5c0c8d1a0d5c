// The membrane stage (assembly + factor + solve) beside bare factors + solves of the same
// reduced matrix (CHOLMOD with its own ordering or our nested dissection, our supernodal
// factor), on curved grid meshes of 10k, 100k and 1M triangles.
// Target (issue 3): stage ≤ 1.5 × bare, 1M triangles ≤ 3 s on the 2-core machine.
#include <benchmark/benchmark.h>

#include <cmath>

#include "geometry/differential_operators.h"
#include "problems/membrane.h"
#include "solver/cholmod_solver.h"
#include "solver/nested_dissection.h"
#include "solver/supernodal_cholesky.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

// n × n squares, 2n² triangles, on a shallow dome z = 0.3 n (1 − (2x/n − 1)² )(1 − (2y/n − 1)²).
SurfaceModel CurvedGrid(int n) {
  const double size = n;
  return SurfaceModel(testing::ToMesh(testing::GridSoup(n, [size](double x, double y) {
    const double u = 2.0 * x / size - 1.0, v = 2.0 * y / size - 1.0;
    return 0.3 * size * (1.0 - u * u) * (1.0 - v * v);
  })));
}

VertexConditions FixedBoundary(const SurfaceModel& s) {
  VertexConditions c(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v)
    if (s.is_boundary(v)) c[v] = BoundaryCondition::kFixed;
  return c;
}

int GridSizeFor(int64_t triangles) { return static_cast<int>(std::lround(std::sqrt(triangles / 2.0))); }

void BM_MembraneStage(benchmark::State& state) {
  const SurfaceModel s = CurvedGrid(GridSizeFor(state.range(0)));
  const VertexConditions supports = FixedBoundary(s);
  MembraneSolution solution;
  for (auto _ : state) {
    if (!SolveMembrane(s, supports, MembraneOptions(), 1350.0, &solution).ok()) state.SkipWithError("solve failed");
  }
  state.counters["triangles"] = s.num_faces();
  state.counters["factor_s"] = solution.factor_seconds;
  state.counters["assemble_s"] = solution.assemble_seconds;
}

// The same reduced system the stage solves: interior rows and columns of λ_m K, with the
// interior vertices' points (for nested dissection).
Eigen::SparseMatrix<double> ReducedSystem(const SurfaceModel& s, std::vector<Eigen::Vector3d>* points) {
  const Eigen::SparseMatrix<double> K = CotanStiffness(s);
  std::vector<int> unknown(s.num_vertices(), -1);
  int n = 0;
  for (int v = 0; v < s.num_vertices(); ++v)
    if (!s.is_boundary(v)) unknown[v] = n++, points->push_back(s.position(v));
  std::vector<Eigen::Triplet<double>> t;
  for (int col = 0; col < K.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, col); it; ++it)
      if (unknown[it.row()] >= 0 && unknown[it.col()] >= 0) t.emplace_back(unknown[it.row()], unknown[it.col()], 1e6 * it.value());
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// Factor + solve of the reduced system: CHOLMOD (simplicial) with its own ordering (arg 1 = 0)
// or with our nested dissection (1), or our supernodal factor with nested dissection (2: the
// halves below the top separator on two threads where there are two; 3: one thread).
void BM_FactorSolve(benchmark::State& state) {
  const SurfaceModel s = CurvedGrid(GridSizeFor(state.range(0)));
  std::vector<Eigen::Vector3d> points;
  const Eigen::SparseMatrix<double> A = ReducedSystem(s, &points);
  const std::vector<int> dissection = NestedDissectionOrdering(A, points);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(A.rows(), -1.0);
  Eigen::VectorXd x;
  double flops = 0.0;
  for (auto _ : state) {
    if (state.range(1) >= 2) {
      SupernodalCholesky solver;
      if (state.range(1) == 3) solver.set_threads(1);
      if (!solver.Factorize(A, dissection).ok() || !solver.Solve(b, &x).ok()) state.SkipWithError("failed");
      flops = solver.flops();
    } else {
      CholmodSolver solver;
      if (state.range(1) == 1) solver.SetOrdering(dissection);
      if (!solver.Factorize(A).ok() || !solver.Solve(b, &x).ok()) state.SkipWithError("CHOLMOD failed");
      flops = solver.factor_flops();
    }
  }
  state.counters["triangles"] = s.num_faces();
  state.counters["flops"] = flops;
}

}  // namespace
}  // namespace pqlayout

BENCHMARK(pqlayout::BM_MembraneStage)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(pqlayout::BM_FactorSolve)
    ->ArgsProduct({{10000, 100000, 1000000}, {0, 1, 2, 3}})
    ->ArgNames({"triangles", "factor"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
