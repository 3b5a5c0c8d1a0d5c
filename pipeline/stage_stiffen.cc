// Stage `stiffen`: the planarised grid shell reshaped within stiffen.tolerance so that the
// frame's compliance drops (the optimiser: problems/stiffen.h); with extract.brace_free_edges
// = paying, each free edge stretch is also braced and the shell stiffened again, kept where
// that pays (problems/edge_bracing_choice.h). Writes the final mesh as quads.obj / quads.ply
// (what `analyze` analyses), figures/offset.svg (normal offset from the planarised mesh) and
// the 3D view of the final shell.
#include <glog/logging.h>

#include <functional>
#include <string>
#include <vector>

#include "report/figures.h"
#include "problems/edge_bracing_choice.h"
#include "problems/grid_frame.h"
#include "problems/planarize.h"
#include "pipeline/stages.h"
#include "problems/stiffen.h"

namespace pqlayout {

constexpr double kLittleGain = 0.01;  // a compliance drop below this (relative) is warned about

namespace {

// extract.brace_free_edges = paying: each free stretch's quads cut and the shell stiffened
// again, kept where that lowers the compliance (problems/edge_bracing_choice.h); `report` is
// the kept trial's. bracing: report.json's stages.stiffen.bracing.
Status BraceWherePaysAfterStiffen(const std::vector<Restraints>& restraints,
                                  const std::function<Status(ExtractedMesh*, StiffenReport*)>& stiffen,
                                  ExtractedMesh* shell, StiffenReport* report, nlohmann::json* bracing) {
  std::vector<StiffenReport> reports;
  const auto evaluate = [&](ExtractedMesh* mesh, double* compliance) {
    reports.emplace_back();
    PQ_RETURN_IF_ERROR(stiffen(mesh, &reports.back()));
    *compliance = reports.back().compliance_after;
    return Status::Ok();
  };
  BracingChoice choice;
  PQ_RETURN_IF_ERROR(BraceWherePays(FreeBoundaryVertices(*shell, restraints), evaluate, shell, &choice));
  *report = reports[choice.kept_trial];
  *bracing = {{"free_stretches", choice.stretches},      {"braced_stretches", choice.braced_stretches},
              {"braced_quads", choice.braced_quads},     {"trials", choice.trials},
              {"compliance_unbraced", choice.compliance_unbraced},
              {"compliance_ratio", choice.compliance / choice.compliance_unbraced},
              {"trial_ratios", choice.ratio}};
  if (choice.stretches > 0)
    LOG(INFO) << "stiffen: " << choice.braced_stretches << " of " << choice.stretches
              << " free stretches braced (extract.brace_free_edges = paying: " << choice.braced_quads
              << " quads cut into triangles), compliance after stiffen " << choice.compliance_unbraced << " → "
              << choice.compliance << " J in " << choice.trials << " stiffen runs";
  return Status::Ok();
}

}  // namespace

Status RunStiffenStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  const StiffenOptions& options = state->config.stiffen;
  const double target = state->config.planarize.target_delta;
  state->shell = state->planarized;
  StiffenReport report;
  if (options.tolerance > 0.0)
    LOG(INFO) << "stiffen: vertices may move " << options.tolerance << " m off the reference (and slide "
              << options.slide << " m along it), " << options.max_iterations << " iterations at most";
  const std::vector<Restraints> restraints = VertexRestraints(state->planarized, *state->surface, state->supports);
  const auto stiffen = [&](ExtractedMesh* mesh, StiffenReport* r) {
    return StiffenMesh(*state->surface, restraints, state->config.analysis, options, target,
                       state->config.layout.spacing, mesh, r, &state->buckling_memo);
  };
  nlohmann::json bracing;
  if (state->config.extract.brace_free_edges == "paying") {
    PQ_RETURN_IF_ERROR(BraceWherePaysAfterStiffen(restraints, stiffen, &state->shell, &report, &bracing));
  } else {
    PQ_RETURN_IF_ERROR(stiffen(&state->shell, &report));
  }
  *metrics = report.ToJson();
  if (!bracing.is_null()) (*metrics)["bracing"] = bracing;
  state->normal_offset = report.normal_offset;  // for report.html's 3D view
  (*metrics)["tolerance"] = options.tolerance;
  if (options.tolerance == 0.0) {
    LOG(INFO) << "stiffen: off (stiffen.tolerance = 0); compliance " << report.compliance_before << " J";
    // quads.obj, quads.ply from planarize stand; the offset figure says the stage was off.
    return WriteOffsetFigure(*state->surface, state->shell.mesh, report.normal_offset, 0.0,
                             "Normal offset: none (stiffen.tolerance = 0)", out->Path("figures/offset.svg"));
  }
  LOG(INFO) << "stiffen: compliance " << report.compliance_before << " → " << report.compliance_after << " J (×"
            << report.compliance_ratio << ") in " << report.iterations << " iterations, " << report.evaluations
            << " frame solves; normal offset ≤ " << report.offset_max * 1000.0 << " mm, slide ≤ "
            << report.slide_max * 1000.0 << " mm, δ max " << report.planarity_max
            << ", ≤ " << report.closeness_max * 1000.0 << " mm from the reference, kinks mean "
            << report.kink_mean_deg_before << "° → " << report.kink_mean_deg_after << "°, max "
            << report.kink_max_deg_before << "° → " << report.kink_max_deg_after << "°, steel "
            << report.steel_mass_change * 100.0 << " %";
  // A stage that gains (almost) nothing says why, rather than leaving ×0.99x to be read as
  // "this shell is as stiff as it gets": on the corpus and the Great Court stiffen gains
  // 4–48 %; a Wolfe line search that finds no step it can make planar again gains 0.
  if (!report.kept_planarised && report.compliance_ratio > 1.0 - kLittleGain)
    LOG(WARNING) << "stiffen: the compliance fell by only " << (1.0 - report.compliance_ratio) * 100.0 << " % ("
                 << report.iterations << " iterations; " << report.stop
                 << "): more room (stiffen.tolerance, stiffen.slide) or another layout may do better";
  if (report.planarity_max > target)
    LOG(WARNING) << "stiffen: δ max " << report.planarity_max << " is above planarize.target_delta " << target;
  if (report.closeness_max > options.tolerance)
    LOG(WARNING) << "stiffen: a vertex is " << report.closeness_max << " m from the reference, more than stiffen.tolerance "
                 << options.tolerance << " m: planarize left it there, and stiffen moves such a vertex only inwards (or "
                    "holds it: boundary, no room)";
  const PolyMesh& mesh = state->shell.mesh;
  PQ_RETURN_IF_ERROR(WriteShellMesh(mesh, target, state->origin, out, "quads"));
  PQ_RETURN_IF_ERROR(WriteOffsetFigure(*state->surface, mesh, report.normal_offset, options.tolerance,
                                       "Normal offset of the stiffened shell from the planarised one",
                                       out->Path("figures/offset.svg")));
  std::string title = "The stiffened grid shell, seen from the south-west";
  // bracing is null unless extract.brace_free_edges = paying (none and all decide nothing here).
  if (bracing.is_object() && bracing.value("braced_quads", 0) > 0)  // short enough for the figure's width
    title = "The stiffened shell from the south-west; " + std::to_string(bracing["braced_quads"].get<int>()) +
            " free-edge quads braced";
  return WriteShell3dFigure(*state->surface, mesh, target, title, out->Path("figures/shell_3d.svg"));
}

}  // namespace pqlayout
