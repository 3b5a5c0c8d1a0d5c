// Stage `levelset`: see problems/levelset.h. The problem itself is in problems/levelset_*.cc
// (geometry, initial guess, Ceres terms, solves, metrics; shared declarations in
// levelset_internal.h) and the panel-density scaling in problems/panel_area.h; this file
// applies the scaling when layout.density asks for it and writes the result.
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

#include "geometry/field_writers.h"
#include "report/figures.h"
#include "problems/levelset.h"
#include "problems/panel_area.h"
#include "pipeline/stages.h"

namespace pqlayout {

Status RunLevelsetStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  SurfaceModel& surface = *state->surface;
  LevelSetSolution& solution = state->levelsets;
  const double h = state->config.layout.spacing;
  const WorkingMesh* ahead = state->working_mesh.valid() ? &state->working_mesh.get() : nullptr;
  PQ_RETURN_IF_ERROR(SolveLevelSets(surface, state->guidance, state->config.levelset, h, &solution, ahead));
  const SeamCut* seams = solution.seams.cut.get();
  const SurfaceModel& level_surface = seams != nullptr ? seams->cut() : surface;
  const std::vector<double>& phi_values = seams != nullptr ? solution.phi_cut : solution.phi;
  const std::vector<double>& psi_values = seams != nullptr ? solution.psi_cut : solution.psi;
  double density_scale = 1.0;
  if (state->config.layout.density == "panel_area") {
    density_scale = PanelAreaScale(level_surface, phi_values, psi_values, h);
    PQ_RETURN_IF_ERROR(ScaleLevelSets(density_scale, h, &solution));
    LOG(INFO) << "levelset: φ and ψ scaled by " << density_scale << " for a mean panel area of h²";
  }
  auto phi = surface.VertexField<double>("phi");
  auto psi = surface.VertexField<double>("psi");
  for (int v = 0; v < surface.num_vertices(); ++v) {
    phi[VertexHandle(v)] = solution.phi[v];
    psi[VertexHandle(v)] = solution.psi[v];
  }
  *metrics = solution.metrics.ToJson();
  (*metrics)["initial_guess"] = solution.initial.ToJson();
  (*metrics)["ceres"] = solution.solver;
  (*metrics)["working_mesh_triangles"] = solution.working_faces;
  (*metrics)["working_mesh"] = solution.working_mesh;
  (*metrics)["working_edge"] = solution.working_edge;
  (*metrics)["crossing_rounds_kept"] = solution.crossing_rounds_kept;
  (*metrics)["density_scale"] = density_scale;
  (*metrics)["seams"] = solution.seams.ToJson();
  nlohmann::json poles = nlohmann::json::array();
  for (const LevelSetCap& c : solution.caps)
    poles.push_back({{"centre", {c.centre.x(), c.centre.y(), c.centre.z()}}, {"cap_radius", c.radius}});
  (*metrics)["poles"] = poles;
  if (!solution.rejected_poles.is_null()) (*metrics)["poles_not_kept"] = solution.rejected_poles;
  if (!solution.tip_cone.is_null()) (*metrics)["tip_cone"] = solution.tip_cone;
  if (state->config.output.fields)  // in the background, from copies (base/background_writer.h)
    out->WriteInBackground([phi = solution.phi, psi = solution.psi, path = out->Path("fields/levelsets.csv")] {
      return WriteCsvTable({"id", "phi", "psi"}, {&phi, &psi}, path);
    });
  const auto& m = solution.metrics;
  LOG(INFO) << "levelset: alignment " << m.alignment_rms_deg << "° RMS (" << m.alignment_rms_deg_strong
            << "° where weight > 0.5), spacing CV φ " << m.spacing_cv_phi << " ψ " << m.spacing_cv_psi
            << ", conjugacy " << m.conjugacy_rms << ", min crossing " << m.min_crossing_angle_deg << "° ("
            << m.faces_below_min_angle << " faces below " << state->config.levelset.min_angle << "°), "
            << m.foldovers << " fold-overs";
  // The layout is still written, but the run must say that its quads are not what was asked for.
  if (m.foldovers > 0 || m.faces_below_min_angle > 0) {
    std::ostringstream what;
    what.precision(3);
    what << m.faces_below_min_angle << " faces (" << 100.0 * m.area_below_min_angle << " % of the area) cross below "
         << "levelset.min_angle " << state->config.levelset.min_angle << "° (the smallest at "
         << m.min_crossing_angle_deg << "°): the quads there are sheared";
    if (CrossingOutOfReach(m))
      what << "; more than half the area, beyond what the crossing rounds and the cone's retry can lift (they "
           << "re-solve round the failing faces, and past half the area after the joint solve are not run): a "
           << "smaller levelset.min_angle, or guidance whose conjugate directions cross wider";
    if (m.foldovers > 0) what << "; " << m.foldovers << " faces fold over: the quads there are inverted";
    LOG(WARNING) << "levelset: " << what.str();
  }
  // The figure on the background writer (~0.4 s at a million triangles), from copies of the
  // values and shares of the meshes; the reference is read-only from here on
  // (SurfaceModel::FreezeFields). The sheared faces as report.json counts them: on the remeshed
  // working mesh when the solve ran there without seams (the lines are drawn on the reference,
  // where interpolated values can cross a little differently), else on the mesh the lines are
  // drawn on.
  const bool on_working = seams == nullptr && solution.working != nullptr;
  out->WriteInBackground([reference = std::shared_ptr<const SurfaceModel>(state->surface),
                          seams = solution.seams.cut, working = on_working ? solution.working : nullptr,
                          phi = phi_values, psi = psi_values,
                          phi_working = on_working ? solution.phi_working : std::vector<double>(),
                          psi_working = on_working ? solution.psi_working : std::vector<double>(),
                          direction = state->guidance.direction, weight = state->guidance.weight,
                          singularities = state->guidance.singularities, h,
                          min_angle = state->config.levelset.min_angle, path = out->Path("figures/levelsets.svg")] {
    FigureOptions figure;
    figure.min_crossing_deg = min_angle;
    figure.guidance_singularities = &singularities;
    const SurfaceModel& level_surface = seams != nullptr ? seams->cut() : *reference;
    const SolvedLevelSets solved = working != nullptr ? SolvedLevelSets{*working, phi_working, psi_working}
                                                      : SolvedLevelSets{level_surface, phi, psi};
    return WriteLevelSetFigure(*reference, phi, psi, h, direction, weight,
                               "Level sets: φ (black) aligned with the guidance, ψ (blue) conjugate", path, figure,
                               seams.get(), &solved);
  });
  return Status::Ok();
}

}  // namespace pqlayout
