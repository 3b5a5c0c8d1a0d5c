// Stage `analyze` (paper §4, SPEC §7): the planarised mesh as a rigid-jointed steel frame.
// Nodes = mesh vertices, members = mesh edges (12-DOF Euler–Bernoulli, solver/frame_analysis.h),
// section and material from analysis.*; loads along −z: member self-weight ρ g A L, half to
// each end, and analysis.panel_load × face area (norm of the vector area) split equally
// among the face's vertices. Supports: a vertex on the reference boundary takes the condition
// of the nearest reference boundary vertex (fixed → pinned, clamped → all six DOFs,
// sliding → u_z only, free → none). Mesh edges shorter than the section's depth become
// joints (see GridFrame). With analysis.export_calculix the same model is also
// written as a CalculiX deck, analysis/model.inp (solver/calculix_export.h).
#include <glog/logging.h>

#include <cmath>
#include <limits>

#include "geometry/field_writers.h"
#include "problems/figures.h"
#include "problems/stages.h"
#include "solver/calculix_export.h"
#include "solver/frame_analysis.h"

namespace pqlayout {
namespace {

Restraints SupportOf(BoundaryCondition c) {
  switch (c) {
    case BoundaryCondition::kFixed: return {true, true, true, false, false, false};
    case BoundaryCondition::kClamped: return {true, true, true, true, true, true};
    case BoundaryCondition::kSliding: return {false, false, true, false, false, false};
    case BoundaryCondition::kFree: return {false, false, false, false, false, false};
  }
  return {};
}

// The condition of the reference boundary vertex nearest to p.
BoundaryCondition NearestCondition(const SurfaceModel& surface, const VertexConditions& supports,
                                   const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  BoundaryCondition condition = BoundaryCondition::kFree;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    if (!supports[v]) continue;
    const double d = (surface.position(v) - p).squaredNorm();
    if (d < best) best = d, condition = *supports[v];
  }
  return condition;
}

FrameSection SectionOf(const SectionOptions& s) {
  return s.shape == "rectangular_hollow" ? FrameSection::RectangularHollow(s.width, s.height, s.thickness)
                                         : FrameSection::CircularHollow(s.diameter, s.thickness);
}

// analysis/model.inp: the frame as a CalculiX deck, element and subdivision from the config.
Status WriteCalculixModel(const FrameModel& model, const AnalysisOptions& a, OutputFiles* out) {
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
  return out->WriteText("analysis/model.inp", deck);
}

// The frame of the planarised mesh, and how its mesh vertices map onto the frame's nodes.
// Mesh edges shorter than the section's depth are not beams but joints (artefacts where two
// boundary points nearly coincide: on the 3 m Great Court grid, boundary edges of 0.04 mm to
// 20 mm). Their ends become one node: the vertices' loads add up and the node takes every
// restraint of its vertices. Kept as members, such edges make the stiffness numerically
// singular once their ends may slide (12EI/L³ ≈ 1e20 N/m for L = 0.04 mm), which SolveFrame
// rightly reports as a mechanism although the structure is not one.
struct GridFrame {
  FrameModel model;
  std::vector<int> node_of;             // per mesh vertex: its frame node
  std::vector<double> vertex_load;      // per mesh vertex: load along z, N
  std::vector<std::pair<int, int>> member_vertices;  // per member: its mesh edge's end vertices
  double steel_mass = 0.0;              // kg, every mesh edge
  int joints = 0;                       // mesh edges merged into a node
};

double SectionDepth(const SectionOptions& s) {
  return s.shape == "rectangular_hollow" ? std::max(s.width, s.height) : s.diameter;
}

int Root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

void BuildFrame(const PipelineState& state, GridFrame* frame) {
  const PolyMesh& mesh = state.planarized.mesh;
  const AnalysisOptions& a = state.config.analysis;
  FrameModel& model = frame->model;
  model.section = SectionOf(a.section);
  model.material.youngs_modulus = a.material.youngs_modulus;
  model.material.shear_modulus = a.material.youngs_modulus / (2.0 * (1.0 + a.material.poisson_ratio));
  const int n = static_cast<int>(mesh.n_vertices());
  std::vector<Eigen::Vector3d> point(n), normal(n, Eigen::Vector3d::Zero());
  for (int v = 0; v < n; ++v) point[v] = ToEigen(mesh.point(VertexHandle(v)));
  frame->vertex_load.assign(n, 0.0);
  for (const auto f : mesh.faces()) {
    Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
    std::vector<int> ids;
    for (const auto v : mesh.fv_range(f)) ids.push_back(v.idx());
    for (size_t k = 0; k < ids.size(); ++k) vector_area += 0.5 * point[ids[k]].cross(point[ids[(k + 1) % ids.size()]]);
    const double share = a.panel_load * vector_area.norm() / ids.size();
    for (const int v : ids) {
      frame->vertex_load[v] -= share;
      normal[v] += vector_area;
    }
  }
  // Joints: union the ends of edges shorter than the section's depth.
  std::vector<int> parent(n);
  for (int v = 0; v < n; ++v) parent[v] = v;
  for (const auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const int i = mesh.from_vertex_handle(h).idx(), j = mesh.to_vertex_handle(h).idx();
    if ((point[i] - point[j]).norm() < SectionDepth(a.section)) parent[Root(parent, i)] = Root(parent, j), ++frame->joints;
  }
  frame->node_of.assign(n, -1);
  std::vector<int> count;
  for (int v = 0; v < n; ++v) {
    const int root = Root(parent, v);
    if (frame->node_of[root] < 0) {
      frame->node_of[root] = static_cast<int>(model.nodes.size());
      model.nodes.push_back(Eigen::Vector3d::Zero());
      count.push_back(0);
    }
    const int node = frame->node_of[v] = frame->node_of[root];
    model.nodes[node] += point[v];
    ++count[node];
  }
  for (size_t k = 0; k < model.nodes.size(); ++k) model.nodes[k] /= count[k];
  for (const auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const int i = mesh.from_vertex_handle(h).idx(), j = mesh.to_vertex_handle(h).idx();
    const double mass = a.material.density * model.section.area * (point[i] - point[j]).norm();
    frame->steel_mass += mass;
    frame->vertex_load[i] -= 0.5 * mass * a.gravity;
    frame->vertex_load[j] -= 0.5 * mass * a.gravity;
    if (frame->node_of[i] == frame->node_of[j]) continue;  // a joint
    model.members.push_back({frame->node_of[i], frame->node_of[j], (normal[i] + normal[j]).normalized()});
    frame->member_vertices.emplace_back(i, j);
  }
  model.loads.assign(model.nodes.size(), NodeVector::Zero());
  model.restraints.assign(model.nodes.size(), Restraints{});
  for (int v = 0; v < n; ++v) {
    const int node = frame->node_of[v];
    model.loads[node][2] += frame->vertex_load[v];
    if (!state.planarized.origin[v].on_boundary) continue;
    const Restraints support = SupportOf(NearestCondition(*state.surface, state.supports, point[v]));
    for (int d = 0; d < 6; ++d) model.restraints[node][d] = model.restraints[node][d] || support[d];
  }
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

Status WriteAnalysisTables(const PipelineState& state, const GridFrame& frame, const FrameResult& r,
                           const VertexResults& per_vertex, OutputFiles* out) {
  const PolyMesh& mesh = state.planarized.mesh;
  const size_t n = frame.node_of.size(), m = frame.model.members.size();
  std::vector<double> x(n), y(n), z(n), load(n), ux(n), uy(n), uz(n), c(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = ToEigen(mesh.point(VertexHandle(static_cast<int>(i))));
    x[i] = p.x(), y[i] = p.y(), z[i] = p.z();
    load[i] = frame.vertex_load[i];
    const NodeVector& u = per_vertex.displacement[i];
    ux[i] = u[0], uy[i] = u[1], uz[i] = u[2];
    c[i] = per_vertex.compliance[i];
  }
  PQ_RETURN_IF_ERROR(WriteCsvTable({"id", "x", "y", "z", "load_z", "ux", "uy", "uz", "compliance"},
                                   {&x, &y, &z, &load, &ux, &uy, &uz, &c}, out->Path("analysis/nodes.csv")));
  std::vector<double> a(m), b(m), length(m), axial(m), ma_y(m), ma_z(m), mb_y(m), mb_z(m), torsion(m);
  for (size_t e = 0; e < m; ++e) {
    const auto& f = r.member_end_forces[e];
    const FrameMember& member = frame.model.members[e];
    a[e] = frame.member_vertices[e].first, b[e] = frame.member_vertices[e].second;  // mesh vertex ids
    length[e] = (frame.model.nodes[member.b] - frame.model.nodes[member.a]).norm();
    axial[e] = r.axial_force[e], torsion[e] = f[9];
    ma_y[e] = f[4], ma_z[e] = f[5], mb_y[e] = f[10], mb_z[e] = f[11];
  }
  return WriteCsvTable({"id", "node_a", "node_b", "length", "axial_force", "torsion", "moment_y_a", "moment_z_a",
                        "moment_y_b", "moment_z_b"},
                       {&a, &b, &length, &axial, &torsion, &ma_y, &ma_z, &mb_y, &mb_z}, out->Path("analysis/members.csv"));
}

}  // namespace

Status RunAnalyzeStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  GridFrame frame;
  BuildFrame(*state, &frame);
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
              {"n_members", state->planarized.mesh.n_edges()},
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
  PQ_RETURN_IF_ERROR(WriteAnalysisTables(*state, frame, r, per_vertex, out));
  if (state->config.analysis.export_calculix) PQ_RETURN_IF_ERROR(WriteCalculixModel(model, state->config.analysis, out));
  return WriteComplianceFigure(*state->surface, state->planarized.mesh, per_vertex.compliance, 0.0,
                               "Nodal compliance of the grid shell (" + state->config.guidance.source + " guidance)",
                               out->Path("figures/compliance.svg"));
}

}  // namespace pqlayout
