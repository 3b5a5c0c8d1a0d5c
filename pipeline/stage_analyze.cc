// Stage `analyze` (paper §4, SPEC §7): the final grid shell (stiffened, or planarised when
// stiffen is off) as a rigid-jointed steel frame: problems/grid_frame.h builds the model
// (the same one `stiffen` optimises), solver/frame_analysis.h solves it, and
// problems/structural_checks.h adds buckling, utilisation and deflection. With
// analysis.export_calculix the same model is also written as CalculiX decks,
// analysis/model.inp and (when it buckles) analysis/model_buckle.inp (solver/calculix_export.h).
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/field_writers.h"
#include "report/figures.h"
#include "pipeline/stages.h"
#include "solver/calculix_export.h"
#include "solver/frame_analysis.h"
#include "problems/grid_frame.h"
#include "problems/structural_checks.h"

namespace pqlayout {
namespace {

// analysis/model.inp: the frame as a CalculiX deck, element and subdivision from the config;
// with buckling_modes, analysis/model_buckle.inp: a *BUCKLE deck, B32R (ccx has no U1
// stress stiffness), at least 2 elements per member.
Status WriteCalculixModel(const FrameModel& model, const AnalysisOptions& a, int buckling_modes, OutputFiles* out) {
  CalculixExportOptions options;
  CalculixElementFromName(a.calculix_element, &options.element);  // the config admits u1 | b32r only
  options.subdivisions = a.calculix_subdivisions;
  const bool circular = a.section.shape != "rectangular_hollow";
  options.shape.kind = circular ? CalculixSectionShape::kCircularHollow : CalculixSectionShape::kRectangularHollow;
  options.shape.diameter = a.section.diameter;
  options.shape.width = a.section.width;
  options.shape.height = a.section.height;
  options.shape.thickness = a.section.thickness;
  options.title = "pqlayout analyze: planarised grid shell as a rigid-jointed frame";
  std::string deck;
  PQ_RETURN_IF_ERROR(WriteCalculixDeck(model, options, &deck).WithContext("analysis.export_calculix"));
  PQ_RETURN_IF_ERROR(out->WriteText("analysis/model.inp", deck));
  if (buckling_modes == 0) return Status::Ok();
  options.element = CalculixElement::kB32R;
  options.subdivisions = std::max(2, options.subdivisions);
  options.buckling_modes = buckling_modes;
  options.title = "pqlayout analyze: linear buckling of the grid shell (compare with report.json buckling_factors)";
  PQ_RETURN_IF_ERROR(WriteCalculixDeck(model, options, &deck).WithContext("analysis.export_calculix"));
  return out->WriteText("analysis/model_buckle.inp", deck);
}

// Per mesh vertex: the displacement of its node and its own nodal compliance f_v · u_v.
struct VertexResults {
  std::vector<NodeVector> displacement;
  std::vector<double> compliance;
};

VertexResults ResultsPerVertex(const GridFrame& frame, const FrameResult& r) {
  VertexResults out;
  for (size_t v = 0; v < frame.node_of.size(); ++v) {
    out.displacement.push_back(r.displacement[frame.node_of[v]]);
    out.compliance.push_back(frame.vertex_load[v] * out.displacement.back()[2]);
  }
  return out;
}

// analysis/nodes.csv and analysis/members.csv as columns (kept in PipelineState too).
AnalysisTables BuildAnalysisTables(const PipelineState& state, const GridFrame& frame, const FrameResult& r,
                                   const VertexResults& per_vertex, const std::vector<double>& utilisation) {
  const PolyMesh& mesh = state.shell.mesh;
  const size_t n = frame.node_of.size(), m = frame.model.members.size();
  std::vector<double> x(n), y(n), z(n), load(n), ux(n), uy(n), uz(n), c(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = ToEigen(mesh.point(VertexHandle(static_cast<int>(i)))) + state.origin;  // file's
    x[i] = p.x(), y[i] = p.y(), z[i] = p.z();
    load[i] = frame.vertex_load[i];
    const NodeVector& u = per_vertex.displacement[i];
    ux[i] = u[0], uy[i] = u[1], uz[i] = u[2];
    c[i] = per_vertex.compliance[i];
  }
  AnalysisTables tables;
  tables.nodes = {{"x", x}, {"y", y}, {"z", z}, {"load_z", load}, {"ux", ux}, {"uy", uy}, {"uz", uz}, {"compliance", c}};
  std::vector<double> a(m), b(m), length(m), axial(m), ma_y(m), ma_z(m), mb_y(m), mb_z(m), torsion(m);
  for (size_t e = 0; e < m; ++e) {
    const auto& f = r.member_end_forces[e];
    const FrameMember& member = frame.model.members[e];
    a[e] = frame.member_vertices[e].first, b[e] = frame.member_vertices[e].second;  // mesh vertex ids
    length[e] = (frame.model.nodes[member.b] - frame.model.nodes[member.a]).norm();
    axial[e] = r.axial_force[e], torsion[e] = f[9];
    ma_y[e] = f[4], ma_z[e] = f[5], mb_y[e] = f[10], mb_z[e] = f[11];
  }
  tables.members = {{"node_a", a},         {"node_b", b},         {"length", length},
                    {"axial_force", axial}, {"torsion", torsion},   {"moment_y_a", ma_y},
                    {"moment_z_a", ma_z},   {"moment_y_b", mb_y},   {"moment_z_b", mb_z},
                    {"utilisation", utilisation}};
  return tables;
}

Status WriteColumnTable(const ColumnTable& table, const std::string& path) {
  std::vector<std::string> header = {"id"};
  std::vector<const std::vector<double>*> columns;
  for (const auto& [name, values] : table) header.push_back(name), columns.push_back(&values);
  return WriteCsvTable(header, columns, path);
}

// The engineering checks' files: analysis/buckling_modes.csv, figures/buckling.svg (first mode),
// figures/utilisation.svg.
Status WriteStructuralChecks(const SurfaceModel& surface, const PolyMesh& mesh, const GridFrame& frame,
                             const StructuralChecks& c, const std::string& guidance, OutputFiles* out) {
  PQ_RETURN_IF_ERROR(WriteUtilisationFigure(surface, mesh, frame.member_vertices, c.utilisation,
                                            "Member utilisation η (" + guidance + " guidance)",
                                            out->Path("figures/utilisation.svg")));
  if (!c.buckling.buckles) return Status::Ok();
  const size_t n = frame.node_of.size();
  std::vector<std::vector<double>> columns;
  std::vector<std::string> header{"id"};
  for (size_t k = 0; k < c.buckling.modes.size(); ++k)
    for (const char* axis : {"ux", "uy", "uz"}) header.push_back("mode" + std::to_string(k + 1) + "_" + axis);
  columns.resize(header.size() - 1, std::vector<double>(n));
  std::vector<double> amplitude(n);
  for (size_t v = 0; v < n; ++v) {
    for (size_t k = 0; k < c.buckling.modes.size(); ++k)
      for (int d = 0; d < 3; ++d) columns[3 * k + d][v] = c.buckling.modes[k][frame.node_of[v]][d];
    amplitude[v] = c.buckling.modes[0][frame.node_of[v]].head<3>().norm();
  }
  std::vector<const std::vector<double>*> pointers;
  for (const auto& column : columns) pointers.push_back(&column);
  PQ_RETURN_IF_ERROR(WriteCsvTable(header, pointers, out->Path("analysis/buckling_modes.csv")));
  std::ostringstream title;
  title.precision(3);
  title << "First buckling mode, λ = " << c.buckling.factors.front() << " (" << guidance << " guidance)";
  return WriteBucklingFigure(surface, mesh, amplitude, title.str(), out->Path("figures/buckling.svg"));
}

}  // namespace

Status RunAnalyzeStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  GridFrame frame;
  BuildGridFrame(state->shell.mesh, VertexRestraints(state->shell, *state->surface, state->supports),
                 state->config.analysis, &frame);
  const FrameModel& model = frame.model;
  FrameResult r;
  PQ_RETURN_IF_ERROR(SolveFrame(model, &r).WithContext("analyze"));
  const VertexResults per_vertex = ResultsPerVertex(frame, r);
  const size_t n = frame.node_of.size();
  double mean = 0.0, max_c = 0.0, max_u = 0.0, total_load = 0.0;
  for (size_t v = 0; v < n; ++v) {
    mean += per_vertex.compliance[v] / n;
    max_c = std::max(max_c, per_vertex.compliance[v]);
    max_u = std::max(max_u, per_vertex.displacement[v].head<3>().norm());
    total_load += frame.vertex_load[v];
  }
  Eigen::Vector3d reactions = Eigen::Vector3d::Zero();
  for (const auto& reaction : r.reaction) reactions += reaction.head<3>();
  int supported = 0;
  for (const auto& restraint : model.restraints) supported += restraint[0] || restraint[1] || restraint[2];
  *metrics = {{"compliance_total", r.compliance},
              {"compliance_node_mean", mean},
              {"compliance_node_max", max_c},
              {"compliance_per_tonne", r.compliance / (frame.steel_mass / 1000.0)},
              {"max_displacement", max_u},
              {"steel_mass", frame.steel_mass},
              {"n_nodes", n},
              {"n_members", state->shell.mesh.n_edges()},
              {"n_frame_nodes", model.nodes.size()},
              {"n_frame_members", model.members.size()},
              {"n_joints", frame.joints},
              {"n_supported_nodes", supported},
              {"total_load", -total_load},
              {"sum_of_reactions", {reactions.x(), reactions.y(), reactions.z()}}};
  LOG(INFO) << "analyze: " << n << " nodes, " << model.members.size() << " members";
  if (supported == static_cast<int>(model.nodes.size()))
    LOG(WARNING) << "analyze: every node of the grid shell is supported, so nothing deflects and the compliance "
                 << r.compliance << " J says nothing about the layout (use a smaller layout.spacing)";
  if (frame.joints > 0)
    LOG(INFO) << "analyze: " << frame.joints << " mesh edge(s) shorter than the section depth "
              << SectionDepth(state->config.analysis.section) << " m merged into joints: " << model.nodes.size()
              << " frame nodes";
  LOG(INFO) << "analyze: steel " << frame.steel_mass / 1000.0 << " t; compliance " << r.compliance << " J (node mean "
            << mean << ", max " << max_c << "), max |u| " << max_u * 1000.0 << " mm";
  StructuralChecks checks;
  PQ_RETURN_IF_ERROR(RunStructuralChecks(frame, r, state->config.analysis, &checks, true, &state->buckling_memo)
                         .WithContext("analyze"));
  metrics->update(checks.ToJson(frame));
  state->analysis = BuildAnalysisTables(*state, frame, r, per_vertex, checks.utilisation);
  PQ_RETURN_IF_ERROR(WriteColumnTable(state->analysis.nodes, out->Path("analysis/nodes.csv")));
  PQ_RETURN_IF_ERROR(WriteColumnTable(state->analysis.members, out->Path("analysis/members.csv")));
  PQ_RETURN_IF_ERROR(
      WriteStructuralChecks(*state->surface, state->shell.mesh, frame, checks, state->config.guidance.source, out));
  if (state->config.analysis.export_calculix) {
    FrameModel in_file_frame = model;  // the deck in the file's coordinates
    for (auto& p : in_file_frame.nodes) p += state->origin;
    PQ_RETURN_IF_ERROR(WriteCalculixModel(in_file_frame, state->config.analysis,
                                          checks.buckling.buckles ? state->config.analysis.buckling_modes : 0, out));
  }
  return WriteComplianceFigure(*state->surface, state->shell.mesh, per_vertex.compliance, 0.0,
                               "Nodal compliance of the grid shell (" + state->config.guidance.source + " guidance)",
                               out->Path("figures/compliance.svg"));
}

}  // namespace pqlayout
