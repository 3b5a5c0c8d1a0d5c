// Stage `membrane`: v_z under dead load (the problem: problems/membrane.h) as a vertex field,
// its metrics and figures/displacement.svg.
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "pipeline/stages.h"
#include "problems/membrane.h"
#include "report/figures.h"

namespace pqlayout {

Status RunMembraneStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  SurfaceModel& surface = *state->surface;
  MembraneSolution solution;
  LOG(INFO) << "membrane: assembling and factoring the stiffness on " << surface.num_vertices()
            << " vertices ...";  // ~4 s at a million triangles
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
              {"ordering", solution.ordering},
              {"factor", solution.factor},
              {"factor_flops", solution.factor_flops},
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
