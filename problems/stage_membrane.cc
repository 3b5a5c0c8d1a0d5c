// Stage `membrane`: see problems/membrane.h.
#include <glog/logging.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include "geometry/differential_operators.h"
#include "report/figures.h"
#include "problems/membrane.h"
#include "problems/stages.h"
#include "solver/cholmod_solver.h"

namespace pqlayout {
namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

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

  const Eigen::SparseMatrix<double> K = CotanStiffness(surface);
  std::vector<Eigen::Triplet<double>> reduced;
  reduced.reserve(K.nonZeros());
  for (int col = 0; col < K.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, col); it; ++it)
      if (unknown[it.row()] >= 0 && unknown[it.col()] >= 0)
        reduced.emplace_back(unknown[it.row()], unknown[it.col()], options.stiffness * it.value());
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(reduced.begin(), reduced.end());
  Eigen::VectorXd f(n);
  for (int v = 0; v < nv; ++v)
    if (unknown[v] >= 0) f[unknown[v]] = -q * surface.vertex_area(v);
  solution->assemble_seconds = Seconds(start);

  start = std::chrono::steady_clock::now();
  CholmodSolver solver;
  PQ_RETURN_IF_ERROR(solver.Factorize(A).WithContext("membrane"));
  solution->factor_seconds = Seconds(start);
  start = std::chrono::steady_clock::now();
  Eigen::VectorXd x;
  PQ_RETURN_IF_ERROR(solver.Solve(f, &x).WithContext("membrane"));
  solution->solve_seconds = Seconds(start);
  solution->relative_residual = (A * x - f).norm() / f.norm();
  for (int v = 0; v < nv; ++v)
    if (unknown[v] >= 0) solution->v_z[v] = x[unknown[v]];
  return Status::Ok();
}

Status RunMembraneStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  SurfaceModel& surface = *state->surface;
  MembraneSolution solution;
  PQ_RETURN_IF_ERROR(SolveMembrane(surface, state->supports, state->config.membrane, state->config.load.q, &solution));
  auto v_z = surface.VertexField<double>("v_z");
  double max_abs = 0.0, min_v = 0.0;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    v_z[VertexHandle(v)] = solution.v_z[v];
    max_abs = std::max(max_abs, std::abs(solution.v_z[v]));
    min_v = std::min(min_v, solution.v_z[v]);
  }
  *metrics = {{"max_displacement", max_abs},
              {"min_v_z", min_v},
              {"n_dirichlet", solution.n_dirichlet},
              {"n_unknowns", solution.n_unknowns},
              {"relative_residual", solution.relative_residual},
              {"assemble_seconds", solution.assemble_seconds},
              {"factor_seconds", solution.factor_seconds},
              {"solve_seconds", solution.solve_seconds}};
  LOG(INFO) << "membrane: " << solution.n_unknowns << " unknowns, " << solution.n_dirichlet
            << " Dirichlet vertices; max |v_z| " << max_abs * 1000.0 << " mm (factor "
            << solution.factor_seconds << " s, residual " << solution.relative_residual << ")";
  std::ostringstream q;  // not via int: a large q would overflow the cast
  q << state->config.load.q;
  return WriteDisplacementFigure(surface, solution.v_z,
                                 "Membrane displacement v_z under dead load q = " + q.str() + " N/m²",
                                 out->Path("figures/displacement.svg"));
}

}  // namespace pqlayout
