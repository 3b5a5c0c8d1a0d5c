// Stage `planarize`: the extracted quads made planar (the problem: problems/planarize.h), written as
// quads_planarized.{obj,ply} and, until stiffen replaces them, quads.{obj,ply}, with the
// planarity and 3D figures.
#include <glog/logging.h>

#include <algorithm>

#include "geometry/mesh_io.h"
#include "pipeline/stages.h"
#include "problems/planarize.h"
#include "report/figures.h"

namespace pqlayout {

Status WriteShellMesh(const PolyMesh& shell, double target_delta, OutputFiles* out, const std::string& name) {
  PQ_RETURN_IF_ERROR(WriteMesh(shell, out->Path(name + ".obj")));
  PolyMesh mesh = shell;
  mesh.request_face_colors();
  const std::vector<double> delta = FacePlanarity(mesh);
  for (const auto f : mesh.faces()) {
    const double t = std::clamp(delta[f.idx()] / (10.0 * target_delta), 0.0, 1.0);
    mesh.set_color(f, OpenMesh::Vec3uc(static_cast<unsigned char>(255 * t), 64, static_cast<unsigned char>(255 * (1 - t))));
  }
  return WriteMesh(mesh, out->Path(name + ".ply"));
}

Status RunPlanarizeStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  PlanarizeReport report;
  state->planarized = state->quads;
  PQ_RETURN_IF_ERROR(PlanarizeMesh(*state->surface, state->config.planarize, state->config.layout.spacing,
                                   &state->planarized, &report, state->config.extract.min_edge));
  *metrics = report.ToJson();
  const double h = state->config.layout.spacing;
  if (report.planarity_max > state->config.planarize.target_delta)
    LOG(WARNING) << "planarize: δ max " << report.planarity_max << " is above planarize.target_delta "
                 << state->config.planarize.target_delta << " after " << report.rounds << " rounds";
  LOG(INFO) << "planarize: δ max " << report.planarity_max << " (mean " << report.planarity_mean << "), closeness max "
            << report.closeness_max / h << " h, boundary " << report.boundary_deviation / h << " h, moved ≤ "
            << report.max_displacement / h << " h";
  if (report.folded_faces > 0 || report.edges_below_min_edge > 0)
    LOG(WARNING) << "planarize: planarity was bought with panel shape: " << report.folded_faces
                 << " panels convex when extracted are folded or have a reflex corner now, and "
                 << report.edges_below_min_edge << " edges are shorter than extract.min_edge (the shortest "
                 << report.edge_length_min << " h): the layout is not conjugate enough there";
  PolyMesh& mesh = state->planarized.mesh;
  const double target = state->config.planarize.target_delta;
  PQ_RETURN_IF_ERROR(WriteShellMesh(mesh, target, out, "quads_planarized"));
  PQ_RETURN_IF_ERROR(WriteShellMesh(mesh, target, out, "quads"));  // the final mesh until stiffen replaces it
  PQ_RETURN_IF_ERROR(WritePlanarityFigure(*state->surface, mesh, target, "Planarity δ after planarisation",
                                          out->Path("figures/planarity.svg")));
  return WriteShell3dFigure(*state->surface, mesh, target, "The grid shell, seen from the south-west",
                            out->Path("figures/shell_3d.svg"));
}

}  // namespace pqlayout
