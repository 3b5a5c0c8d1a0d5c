// Stage `analyze` (paper §4, SPEC §7): the planarised mesh as a rigid-jointed steel frame.
// Nodes = mesh vertices, members = mesh edges (12-DOF Euler–Bernoulli, solver/frame_analysis.h),
// section and material from analysis.*; loads along −z: member self-weight ρ g A L, half to
// each end, and analysis.panel_load × face area (norm of the vector area) split equally
// among the face's vertices. Supports: a vertex on the reference boundary takes the condition
// of the nearest reference boundary vertex (fixed → pinned, clamped → all six DOFs,
// sliding → u_z only, free → none).
#include <glog/logging.h>

#include <cmath>
#include <limits>

#include "geometry/field_writers.h"
#include "problems/figures.h"
#include "problems/stages.h"
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

FrameModel BuildFrame(const PipelineState& state, double* steel_mass) {
  const PolyMesh& mesh = state.planarized.mesh;
  const AnalysisOptions& a = state.config.analysis;
  FrameModel model;
  model.section = SectionOf(a.section);
  model.material.youngs_modulus = a.material.youngs_modulus;
  model.material.shear_modulus = a.material.youngs_modulus / (2.0 * (1.0 + a.material.poisson_ratio));
  const int n = static_cast<int>(mesh.n_vertices());
  model.nodes.resize(n);
  model.loads.assign(n, NodeVector::Zero());
  model.restraints.assign(n, Restraints{});
  std::vector<Eigen::Vector3d> normal(n, Eigen::Vector3d::Zero());
  for (int v = 0; v < n; ++v) model.nodes[v] = ToEigen(mesh.point(VertexHandle(v)));
  for (const auto f : mesh.faces()) {
    Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
    std::vector<int> ids;
    for (const auto v : mesh.fv_range(f)) ids.push_back(v.idx());
    for (size_t k = 0; k < ids.size(); ++k)
      vector_area += 0.5 * model.nodes[ids[k]].cross(model.nodes[ids[(k + 1) % ids.size()]]);
    const double share = a.panel_load * vector_area.norm() / ids.size();
    for (const int v : ids) {
      model.loads[v][2] -= share;
      normal[v] += vector_area;
    }
  }
  *steel_mass = 0.0;
  for (const auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const int i = mesh.from_vertex_handle(h).idx(), j = mesh.to_vertex_handle(h).idx();
    const double length = (model.nodes[i] - model.nodes[j]).norm();
    const double mass = a.material.density * model.section.area * length;
    *steel_mass += mass;
    model.loads[i][2] -= 0.5 * mass * a.gravity;
    model.loads[j][2] -= 0.5 * mass * a.gravity;
    model.members.push_back({i, j, (normal[i] + normal[j]).normalized()});
  }
  for (int v = 0; v < n; ++v)
    if (state.planarized.origin[v].on_boundary)
      model.restraints[v] = SupportOf(NearestCondition(*state.surface, state.supports, model.nodes[v]));
  return model;
}

Status WriteAnalysisTables(const FrameModel& model, const FrameResult& r, OutputFiles* out) {
  const size_t n = model.nodes.size(), m = model.members.size();
  std::vector<double> x(n), y(n), z(n), load(n), ux(n), uy(n), uz(n), c(n);
  for (size_t i = 0; i < n; ++i) {
    x[i] = model.nodes[i].x(), y[i] = model.nodes[i].y(), z[i] = model.nodes[i].z();
    load[i] = model.loads[i][2];
    ux[i] = r.displacement[i][0], uy[i] = r.displacement[i][1], uz[i] = r.displacement[i][2];
    c[i] = r.nodal_compliance[i];
  }
  PQ_RETURN_IF_ERROR(WriteCsvTable({"id", "x", "y", "z", "load_z", "ux", "uy", "uz", "compliance"},
                                   {&x, &y, &z, &load, &ux, &uy, &uz, &c}, out->Path("analysis/nodes.csv")));
  std::vector<double> a(m), b(m), length(m), axial(m), ma_y(m), ma_z(m), mb_y(m), mb_z(m), torsion(m);
  for (size_t e = 0; e < m; ++e) {
    const auto& f = r.member_end_forces[e];
    a[e] = model.members[e].a, b[e] = model.members[e].b;
    length[e] = (model.nodes[model.members[e].b] - model.nodes[model.members[e].a]).norm();
    axial[e] = r.axial_force[e], torsion[e] = f[9];
    ma_y[e] = f[4], ma_z[e] = f[5], mb_y[e] = f[10], mb_z[e] = f[11];
  }
  return WriteCsvTable({"id", "node_a", "node_b", "length", "axial_force", "torsion", "moment_y_a", "moment_z_a",
                        "moment_y_b", "moment_z_b"},
                       {&a, &b, &length, &axial, &torsion, &ma_y, &ma_z, &mb_y, &mb_z}, out->Path("analysis/members.csv"));
}

}  // namespace

Status RunAnalyzeStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  double steel_mass = 0.0;
  const FrameModel model = BuildFrame(*state, &steel_mass);
  FrameResult r;
  PQ_RETURN_IF_ERROR(SolveFrame(model, &r).WithContext("analyze"));
  double mean = 0.0, max_c = 0.0, max_u = 0.0, total_load = 0.0;
  Eigen::Vector3d reactions = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    mean += r.nodal_compliance[i] / model.nodes.size();
    max_c = std::max(max_c, r.nodal_compliance[i]);
    max_u = std::max(max_u, r.displacement[i].head<3>().norm());
    total_load += model.loads[i][2];
    reactions += r.reaction[i].head<3>();
  }
  int supported = 0;
  for (const auto& restraint : model.restraints) supported += restraint[0] || restraint[1] || restraint[2];
  *metrics = {{"compliance_total", r.compliance},
              {"compliance_node_mean", mean},
              {"compliance_node_max", max_c},
              {"compliance_per_tonne", r.compliance / (steel_mass / 1000.0)},
              {"max_displacement", max_u},
              {"steel_mass", steel_mass},
              {"n_nodes", model.nodes.size()},
              {"n_members", model.members.size()},
              {"n_supported_nodes", supported},
              {"total_load", -total_load},
              {"sum_of_reactions", {reactions.x(), reactions.y(), reactions.z()}}};
  LOG(INFO) << "analyze: " << model.nodes.size() << " nodes, " << model.members.size() << " members, steel "
            << steel_mass / 1000.0 << " t; compliance " << r.compliance << " J (node mean " << mean << ", max " << max_c
            << "), max |u| " << max_u * 1000.0 << " mm";
  PQ_RETURN_IF_ERROR(WriteAnalysisTables(model, r, out));
  return WriteComplianceFigure(*state->surface, state->planarized.mesh, r.nodal_compliance, 0.0,
                               "Nodal compliance of the grid shell (" + state->config.guidance.source + " guidance)",
                               out->Path("figures/compliance.svg"));
}

}  // namespace pqlayout
