#include "problems/grid_frame.h"

#include <ceres/jet.h>

#include <limits>

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

int Root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

std::vector<Eigen::Vector3d> Points(const PolyMesh& mesh) {
  std::vector<Eigen::Vector3d> point(mesh.n_vertices());
  for (const auto v : mesh.vertices()) point[v.idx()] = ToEigen(mesh.point(v));
  return point;
}

std::vector<int> FaceVertices(const PolyMesh& mesh, FaceHandle f) {
  std::vector<int> ids;
  for (const auto v : mesh.fv_range(f)) ids.push_back(v.idx());
  return ids;
}

Eigen::Vector3d VectorArea(const std::vector<Eigen::Vector3d>& point, const std::vector<int>& ids) {
  Eigen::Vector3d area = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < ids.size(); ++k) area += 0.5 * point[ids[k]].cross(point[ids[(k + 1) % ids.size()]]);
  return area;
}

std::pair<int, int> EdgeEnds(const PolyMesh& mesh, EdgeHandle e) {
  const auto h = mesh.halfedge_handle(e, 0);
  return {mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx()};
}

// Per vertex Σ of the vector areas of its faces (the members' orientation, header).
std::vector<Eigen::Vector3d> VertexNormals(const PolyMesh& mesh, const std::vector<Eigen::Vector3d>& point) {
  std::vector<Eigen::Vector3d> normal(point.size(), Eigen::Vector3d::Zero());
  for (const auto f : mesh.faces()) {
    const auto ids = FaceVertices(mesh, f);
    const Eigen::Vector3d area = VectorArea(point, ids);
    for (const int v : ids) normal[v] += area;
  }
  return normal;
}

}  // namespace

FrameSection SectionOf(const SectionOptions& s) {
  return s.shape == "rectangular_hollow" ? FrameSection::RectangularHollow(s.width, s.height, s.thickness)
                                         : FrameSection::CircularHollow(s.diameter, s.thickness);
}

double SectionDepth(const SectionOptions& s) {
  return s.shape == "rectangular_hollow" ? std::max(s.width, s.height) : s.diameter;
}

std::vector<Restraints> VertexRestraints(const ExtractedMesh& mesh, const SurfaceModel& surface,
                                         const VertexConditions& supports) {
  std::vector<Restraints> out(mesh.mesh.n_vertices(), Restraints{});
  for (const auto v : mesh.mesh.vertices())
    if (mesh.origin[v.idx()].on_boundary)
      out[v.idx()] = SupportOf(NearestCondition(surface, supports, ToEigen(mesh.mesh.point(v))));
  return out;
}

void BuildGridFrame(const PolyMesh& mesh, const std::vector<Restraints>& vertex_restraints, const AnalysisOptions& a,
                    GridFrame* frame, const std::vector<bool>* joint_edges) {
  FrameModel& model = frame->model;
  model.section = SectionOf(a.section);
  model.material.youngs_modulus = a.material.youngs_modulus;
  model.material.shear_modulus = a.material.youngs_modulus / (2.0 * (1.0 + a.material.poisson_ratio));
  const int n = static_cast<int>(mesh.n_vertices());
  const std::vector<Eigen::Vector3d> point = Points(mesh);
  const std::vector<Eigen::Vector3d> normal = VertexNormals(mesh, point);
  frame->vertex_load.assign(n, 0.0);
  for (const auto f : mesh.faces()) {
    const auto ids = FaceVertices(mesh, f);
    const double share = a.panel_load * VectorArea(point, ids).norm() / ids.size();
    for (const int v : ids) frame->vertex_load[v] -= share;
  }
  // Joints: union the ends of edges shorter than the section's depth.
  std::vector<int> parent(n);
  for (int v = 0; v < n; ++v) parent[v] = v;
  for (const auto e : mesh.edges()) {
    const auto [i, j] = EdgeEnds(mesh, e);
    const bool joint = joint_edges != nullptr ? (*joint_edges)[e.idx()] : (point[i] - point[j]).norm() < SectionDepth(a.section);
    if (joint) parent[Root(parent, i)] = Root(parent, j), ++frame->joints;
  }
  frame->node_of.assign(n, -1);
  for (int v = 0; v < n; ++v) {
    const int root = Root(parent, v);
    if (frame->node_of[root] < 0) {
      frame->node_of[root] = static_cast<int>(model.nodes.size());
      model.nodes.push_back(Eigen::Vector3d::Zero());
      frame->node_size.push_back(0);
    }
    const int node = frame->node_of[v] = frame->node_of[root];
    model.nodes[node] += point[v];
    ++frame->node_size[node];
  }
  for (size_t k = 0; k < model.nodes.size(); ++k) model.nodes[k] /= frame->node_size[k];
  for (const auto e : mesh.edges()) {
    const auto [i, j] = EdgeEnds(mesh, e);
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
    for (int d = 0; d < 6; ++d) model.restraints[node][d] = model.restraints[node][d] || vertex_restraints[v][d];
  }
}

namespace {

using Jet9 = ceres::Jet<double, 9>;

// −uᵀ(∂K/∂x)u of every member: to its end nodes (node_gradient) and, through the
// orientation vector N_i + N_j, to its end vertices' normals (normal_gradient).
void StiffnessTerms(const GridFrame& frame, const FrameResult& r,
                    const std::vector<Eigen::Vector3d>& normal, std::vector<Eigen::Vector3d>* node_gradient,
                    std::vector<Eigen::Vector3d>* normal_gradient) {
  const FrameModel& model = frame.model;
  for (size_t e = 0; e < model.members.size(); ++e) {
    const FrameMember& member = model.members[e];
    const auto [i, j] = frame.member_vertices[e];
    Eigen::Matrix<Jet9, 3, 1> xa, xb, up;
    const Eigen::Vector3d w = normal[i] + normal[j];
    for (int k = 0; k < 3; ++k) {
      xa[k] = Jet9(model.nodes[member.a][k], k);
      xb[k] = Jet9(model.nodes[member.b][k], 3 + k);
      up[k] = Jet9(w[k], 6 + k);
    }
    Eigen::Matrix<double, 12, 1> u;
    u << r.displacement[member.a], r.displacement[member.b];
    const Jet9 energy = BeamEnergyTwice<Jet9>(xa, xb, up, u, model.section, model.material);
    (*node_gradient)[member.a] -= energy.v.segment<3>(0);
    (*node_gradient)[member.b] -= energy.v.segment<3>(3);
    (*normal_gradient)[i] -= energy.v.segment<3>(6);
    (*normal_gradient)[j] -= energy.v.segment<3>(6);
  }
}

}  // namespace

Status EvaluateGridCompliance(const PolyMesh& mesh, const std::vector<Restraints>& vertex_restraints,
                              const AnalysisOptions& a, bool with_gradient, GridCompliance* out,
                              FrameWorkspace* reuse, const std::vector<bool>* joint_edges) {
  out->frame = GridFrame();
  BuildGridFrame(mesh, vertex_restraints, a, &out->frame, joint_edges);
  PQ_RETURN_IF_ERROR(SolveFrame(out->frame.model, &out->result, reuse));
  out->compliance = out->result.compliance;
  out->gradient.clear();
  if (!with_gradient) return Status::Ok();
  const GridFrame& frame = out->frame;
  const std::vector<Eigen::Vector3d> point = Points(mesh);
  const std::vector<Eigen::Vector3d> normal = VertexNormals(mesh, point);
  const size_t n = point.size();
  std::vector<Eigen::Vector3d> node_gradient(frame.model.nodes.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> normal_gradient(n, Eigen::Vector3d::Zero());
  StiffnessTerms(frame, out->result, normal, &node_gradient, &normal_gradient);
  auto uz = [&](int v) { return out->result.displacement[frame.node_of[v]][2]; };
  std::vector<Eigen::Vector3d>& g = out->gradient;
  g.assign(n, Eigen::Vector3d::Zero());
  for (size_t v = 0; v < n; ++v) g[v] += node_gradient[frame.node_of[v]] / frame.node_size[frame.node_of[v]];
  // Faces: the orientation vectors (through N_v) and the panel load 2 uᵀ ∂f/∂x.
  for (const auto f : mesh.faces()) {
    const auto ids = FaceVertices(mesh, f);
    const size_t k = ids.size();
    const Eigen::Vector3d area = VectorArea(point, ids);
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    double uz_sum = 0.0;
    for (const int v : ids) w += normal_gradient[v], uz_sum += uz(v);
    const Eigen::Vector3d load_direction = 2.0 * uz_sum * (-a.panel_load / k) * area.normalized();
    for (size_t c = 0; c < k; ++c) {
      const Eigen::Vector3d d = 0.5 * (point[ids[(c + k - 1) % k]] - point[ids[(c + 1) % k]]);
      g[ids[c]] += (w + load_direction).cross(d);
    }
  }
  // Edges: member self-weight, 2 uᵀ ∂f/∂x with f_z = −½ ρ g A L at each end.
  const double weight_per_length = a.material.density * frame.model.section.area * a.gravity;
  for (const auto e : mesh.edges()) {
    const auto [i, j] = EdgeEnds(mesh, e);
    const Eigen::Vector3d t = (point[i] - point[j]).normalized();
    const double coefficient = 2.0 * (uz(i) + uz(j)) * (-0.5 * weight_per_length);
    g[i] += coefficient * t;
    g[j] -= coefficient * t;
  }
  return Status::Ok();
}

}  // namespace pqlayout
