// The membrane problem: see problems/membrane.h.
#include <glog/logging.h>

#include <chrono>
#include <cmath>

#include "geometry/differential_operators.h"
#include "problems/membrane.h"
#include "solver/cholmod_solver.h"
#include "solver/nested_dissection.h"
#include "solver/supernodal_cholesky.h"

namespace pqlayout {
namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// From this many unknowns on, the factor's rows are ordered by our nested dissection instead
// of CHOLMOD's AMD (solver/nested_dissection.h). On the Great Court's lattice-seeded references
// (benchmarks/RESULTS.md, "The membrane's ordering"): 479k unknowns (962k triangles) 1.06e10 →
// 4.8e9 flops, stage 7.4–8.1 → 4.1–5.2 s; 153k unknowns 1.5e9 → 8.5e8 flops. Below it (every
// corpus roof, the default Great Court, 44k and 112k references) CHOLMOD's choice stands and
// results are unchanged to the bit; on small regular grids AMD needs fewer flops.
// From the same size on, the factor is our supernodal one (solver/supernodal_cholesky.h)
// instead of CHOLMOD's simplicial one: at 479k unknowns 4.0–4.3 s → see benchmarks/RESULTS.md,
// "The membrane's supernodal factor"; below it CHOLMOD's, so that small runs keep their bits.
constexpr int kNestedDissectionFrom = 100000;

bool IsDirichlet(const std::optional<BoundaryCondition>& c) {
  return c && *c != BoundaryCondition::kFree;
}

Status CheckEveryComponentIsSupported(const SurfaceModel& surface, const VertexConditions& supports) {
  std::vector<int> component;
  const int count = ConnectedComponents(surface, &component);
  std::vector<char> supported(count, 0);
  for (int v = 0; v < surface.num_vertices(); ++v)
    if (IsDirichlet(supports[v])) supported[component[v]] = 1;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    if (!supported[component[v]]) {
      const long size = std::count(component.begin(), component.end(), component[v]);
      return Status::InvalidInput("the part of the surface containing vertex " + std::to_string(v) + " (" +
                                  std::to_string(size) + " vertices) has no fixed, clamped or sliding boundary "
                                  "vertex: the membrane problem is singular (check boundary.default / boundary.rules)");
    }
  }
  return Status::Ok();
}

}  // namespace

Status SolveMembrane(const SurfaceModel& surface, const VertexConditions& supports,
                     const MembraneOptions& options, double q, MembraneSolution* solution) {
  if (options.bending != 0.0)
    return Status::InvalidInput("membrane.bending: the bending term is not implemented yet; use 0 (the paper's model)");
  PQ_RETURN_IF_ERROR(CheckEveryComponentIsSupported(surface, supports));
  auto start = std::chrono::steady_clock::now();
  const int nv = surface.num_vertices();
  // Unknowns: the vertices that are not Dirichlet, numbered consecutively.
  std::vector<int> unknown(nv, -1);
  int n = 0;
  for (int v = 0; v < nv; ++v)
    if (!IsDirichlet(supports[v])) unknown[v] = n++;
  solution->n_unknowns = n;
  solution->n_dirichlet = nv - n;
  solution->v_z.assign(nv, 0.0);
  if (n == 0) return Status::Ok();

  // K without the Dirichlet rows and columns, copied column by column: `unknown` keeps the
  // vertices' order, so each column's rows stay sorted and no triplet sort is needed.
  const Eigen::SparseMatrix<double> K = CotanStiffness(surface);
  std::vector<int> outer(n + 1, 0), inner;
  std::vector<double> values;
  inner.reserve(K.nonZeros());
  values.reserve(K.nonZeros());
  for (int col = 0; col < K.outerSize(); ++col) {
    if (unknown[col] < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, col); it; ++it)
      if (unknown[it.row()] >= 0) {
        inner.push_back(unknown[it.row()]);
        values.push_back(options.stiffness * it.value());
      }
    outer[unknown[col] + 1] = static_cast<int>(inner.size());
  }
  const Eigen::SparseMatrix<double> A =
      Eigen::Map<const Eigen::SparseMatrix<double>>(n, n, static_cast<int>(inner.size()), outer.data(), inner.data(), values.data());
  Eigen::VectorXd f(n);
  for (int v = 0; v < nv; ++v)
    if (unknown[v] >= 0) f[unknown[v]] = -q * surface.vertex_area(v);
  solution->assemble_seconds = Seconds(start);

  start = std::chrono::steady_clock::now();
  Eigen::VectorXd x;
  const bool large = n >= kNestedDissectionFrom;
  SupernodalCholesky supernodal;
  CholmodSolver cholmod;
  if (large) {
    std::vector<Eigen::Vector3d> points(n);
    for (int v = 0; v < nv; ++v)
      if (unknown[v] >= 0) points[unknown[v]] = surface.position(v);
    PQ_RETURN_IF_ERROR(supernodal.Factorize(A, NestedDissectionOrdering(A, points)).WithContext("membrane"));
  } else {
    PQ_RETURN_IF_ERROR(cholmod.Factorize(A).WithContext("membrane"));
  }
  solution->ordering = large ? "nested dissection" : "CHOLMOD";
  solution->factor = large ? "supernodal multifrontal" : "CHOLMOD simplicial";
  solution->factor_seconds = Seconds(start);
  solution->factor_flops = large ? supernodal.flops() : cholmod.factor_flops();
  start = std::chrono::steady_clock::now();
  PQ_RETURN_IF_ERROR((large ? supernodal.Solve(f, &x) : cholmod.Solve(f, &x)).WithContext("membrane"));
  solution->solve_seconds = Seconds(start);
  solution->relative_residual = (A * x - f).norm() / f.norm();
  for (int v = 0; v < nv; ++v)
    if (unknown[v] >= 0) solution->v_z[v] = x[unknown[v]];
  return Status::Ok();
}

}  // namespace pqlayout
