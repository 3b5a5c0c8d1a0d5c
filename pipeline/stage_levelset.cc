// Stage `levelset`: see problems/levelset.h. The problem itself is in problems/levelset_*.cc
// (geometry, initial guess, Ceres terms, solves, metrics; shared declarations in
// levelset_internal.h) and the panel-density scaling in problems/panel_area.h; this file
// applies the scaling when layout.density asks for it and writes the result.
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <sstream>

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
  PQ_RETURN_IF_ERROR(SolveLevelSets(surface, state->guidance, state->config.levelset, h, &solution));
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
  FigureOptions figure;
  figure.min_crossing_deg = state->config.levelset.min_angle;
  figure.guidance_singularities = &state->guidance.singularities;
  // The sheared faces as report.json counts them: on the remeshed working mesh when the solve
  // ran there without seams (the lines are drawn on the reference, where interpolated values
  // can cross a little differently), else on the mesh the lines are drawn on.
  const bool on_working = seams == nullptr && solution.working != nullptr;
  const SolvedLevelSets solved{on_working ? *solution.working : level_surface,
                               on_working ? solution.phi_working : phi_values,
                               on_working ? solution.psi_working : psi_values};
  PQ_RETURN_IF_ERROR(WriteLevelSetFigure(surface, phi_values, psi_values, h, state->guidance.direction,
                                         state->guidance.weight,
                                         "Level sets: φ (black) aligned with the guidance, ψ (blue) conjugate",
                                         out->Path("figures/levelsets.svg"), figure, seams, &solved));
  return Status::Ok();
}

}  // namespace pqlayout
