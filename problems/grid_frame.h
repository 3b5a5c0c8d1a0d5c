// The grid shell as a steel frame (SPEC §7): the one model that `analyze` analyses and
// `stiffen` optimises, built from a polygon mesh.
//   nodes = mesh vertices; members = mesh edges (12-DOF beams, solver/beam_element.h), each
//   oriented by the mean vector area of the faces around its two ends; loads along −z:
//   member self-weight ρ g A L, half to each end, and panel_load × |vector area| of each
//   face split equally among its vertices; supports per vertex (VertexRestraints).
//   Joints: a mesh edge shorter than the section's depth is not a member; its ends become
//   one node at their centroid with the sum of their loads and every restraint of its
//   vertices (artefacts where two boundary points nearly coincide: on the 3 m Great Court
//   grid boundary edges of 0.04 mm to 20 mm; kept as members, 12EI/L³ ≈ 1e20 N/m for
//   L = 0.04 mm makes the stiffness numerically singular once their ends may slide).
//
// Compliance gradient (adjoint; K u = f, C = fᵀu, K symmetric so the adjoint state is u):
//   dC/dx = 2 uᵀ ∂f/∂x − uᵀ (∂K/∂x) u
// with, per member e, uᵀ(∂K/∂x)u = ∂/∂x (u_eᵀ K_e(x_a, x_b, up_e) u_e) by ceres::Jet over the
// end-node positions and the orientation vector up_e = N_i + N_j (N_v = Σ vector areas of
// the faces at v, chained to the face vertices by ∂(w·A_f)/∂p_k = ½ w × (p_{k−1} − p_{k+1})),
// and per load term ∂|A_f|/∂p_k = ½ Â_f × (p_{k−1} − p_{k+1}), ∂L/∂p_i = (p_i − p_j)/L.
// A node that is a joint passes 1/n of its gradient to each of its n vertices.
// One factorisation per evaluation. Tested against central finite differences
// (tests/stiffen_test.cc).
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "geometry/mesh.h"
#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"
#include "problems/boundary_conditions.h"
#include "problems/options.h"
#include "solver/frame_analysis.h"

namespace pqlayout {

struct GridFrame {
  FrameModel model;
  std::vector<int> node_of;             // per mesh vertex: its frame node
  std::vector<int> node_size;           // per frame node: how many mesh vertices it merges
  std::vector<double> vertex_load;      // per mesh vertex: load along z, N
  std::vector<std::pair<int, int>> member_vertices;  // per member: its mesh edge's end vertices
  double steel_mass = 0.0;              // kg, every mesh edge
  int joints = 0;                       // mesh edges merged into a node
};

FrameSection SectionOf(const SectionOptions& s);
double SectionDepth(const SectionOptions& s);

// Per mesh vertex: the restraints of the nearest reference boundary vertex's condition
// (fixed → u, clamped → u and θ, sliding → u_z, free → none) for vertices on the reference
// boundary, none elsewhere.
std::vector<Restraints> VertexRestraints(const ExtractedMesh& mesh, const SurfaceModel& surface,
                                         const VertexConditions& supports);

// joint_edges (per mesh edge, optional): which edges are joints; without it, those shorter than
// the section's depth (stiffen keeps its start's choice, so that its objective stays smooth
// while a member's length crosses the depth on the way).
void BuildGridFrame(const PolyMesh& mesh, const std::vector<Restraints>& vertex_restraints, const AnalysisOptions& a,
                    GridFrame* frame, const std::vector<bool>* joint_edges = nullptr);

struct GridCompliance {
  GridFrame frame;
  FrameResult result;
  double compliance = 0.0;                 // C = fᵀu, J
  std::vector<Eigen::Vector3d> gradient;   // dC/dp per mesh vertex, J/m (when asked for)
};

// Builds and solves the frame of `mesh`; with `with_gradient`, also dC/dp (header comment).
// reuse: see SolveFrame.
Status EvaluateGridCompliance(const PolyMesh& mesh, const std::vector<Restraints>& vertex_restraints,
                              const AnalysisOptions& a, bool with_gradient, GridCompliance* out,
                              FrameWorkspace* reuse = nullptr, const std::vector<bool>* joint_edges = nullptr);

}  // namespace pqlayout
