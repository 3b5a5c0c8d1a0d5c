// Linear static analysis of a rigid-jointed 3D frame (SPEC §7): nodes with 6 DOFs
// (u_x, u_y, u_z, θ_x, θ_y, θ_z), members as 12-DOF Euler–Bernoulli beams (axial, torsion,
// bending in two planes, no shear deformation), supports as restrained DOFs, nodal loads.
// The stiffness matrix is assembled in world coordinates and solved with CHOLMOD; a frame
// that is a mechanism (singular or numerically singular stiffness) is refused, naming a
// node and DOF of the unsupported part.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/Geometry>

#include "base/status.h"
#include "solver/beam_element.h"

namespace pqlayout {

struct FrameMember {
  int a = -1, b = -1;  // end nodes
  // Orientation of the section: local x runs from a to b; local z is this vector projected
  // onto the plane normal to x (for a grid shell: the surface normal); local y = z × x.
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
};

// DOF order per node: u_x, u_y, u_z, θ_x, θ_y, θ_z.
using NodeVector = Eigen::Matrix<double, 6, 1>;
using Restraints = std::array<bool, 6>;

struct FrameModel {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<FrameMember> members;
  std::vector<Restraints> restraints;  // per node; empty = none restrained
  std::vector<NodeVector> loads;       // per node: forces (N) and moments (N·m)
  FrameSection section;
  FrameMaterial material;
};

struct FrameResult {
  std::vector<NodeVector> displacement;  // per node
  std::vector<NodeVector> reaction;      // per node (zero where nothing is restrained)
  // Member end forces in local coordinates: [N_a, V_ya, V_za, T_a, M_ya, M_za, N_b, ...]
  // acting on the member at its ends.
  std::vector<Eigen::Matrix<double, 12, 1>> member_end_forces;
  std::vector<double> axial_force;       // per member, tension positive, N
  double compliance = 0.0;               // fᵀu over all DOFs, J
  std::vector<double> nodal_compliance;  // f_i · u_i (translations), J
};

// Names a DOF for messages: "u_x", ..., "θ_z".
const char* DofName(int dof);

// A frame's free DOFs and its stiffness matrix (SolveFrame's; the buckling solve's).
struct FrameSystem {
  std::vector<int> index;  // per DOF (6 · node + d): its number among the free DOFs, −1 where restrained
  int free = 0;
  // Over the free DOFs (index), or, assembled with every_dof, over all 6 per node (row 6 · node +
  // d), a restrained DOF's row and column then the identity times the members' largest diagonal entry.
  Eigen::SparseMatrix<double> K;
  std::vector<Eigen::Matrix<double, 12, 12>> member_k, member_t;  // per member: local stiffness, T (local = T world)
};
// Checks the model (InvalidInput naming the member) and assembles K.
Status AssembleFrame(const FrameModel& model, FrameSystem* system, bool every_dof = false);

class BlockCholesky;
// Factors K over every DOF in 6 × 6 node blocks (solver/block_cholesky.h: 3–4× CHOLMOD's
// simplicial factor on these frames, the same bits on every machine). reuse (optional): a
// factorisation kept across calls; a frame with the previous call's members and supports then
// keeps its symbolic analysis.
Status SolveFrame(const FrameModel& model, FrameResult* result, BlockCholesky* reuse = nullptr);

}  // namespace pqlayout
