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
#include "solver/block_cholesky.h"
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
// K's compressed pattern for one topology (members' ends, supports, numbering) and, per member,
// the slot in K's values of each of its 144 entries (−1: a restrained row or column), so that a
// frame of the same topology is assembled by adding into the slots in member order: the sums
// of the triplet assembly, whose duplicates Eigen adds in the same order, so the same bits,
// without its sort (~18 % of a stiffen evaluation).
struct FramePattern {
  std::vector<int> ends;           // the topology: node count, every_dof, members' ends, restraint flags
  std::vector<int> outer, inner;   // K's pattern
  std::vector<int> slots;          // 144 per member, row-major (p, q)
  std::vector<int> restrained;     // over every DOF: the slot of each restrained DOF's diagonal
  std::vector<char> added;         // scratch: whether a slot holds its first term yet
};

// Checks the model (InvalidInput naming the member) and assembles K. pattern (optional): kept
// across calls; used when the model's topology is the one it was made for, else made anew.
Status AssembleFrame(const FrameModel& model, FrameSystem* system, bool every_dof = false,
                     FramePattern* pattern = nullptr);

// What SolveFrame keeps across calls on frames of one topology (stiffen's evaluations): K's
// pattern, the factor's symbolic analysis, and the system's storage (K and the members' 12 × 12
// matrices: 46 MB at 20k members, which allocated afresh cost the kernel's page zeroing, ~8 % of
// a stiffen evaluation at h = 1 m).
struct FrameWorkspace {
  FramePattern pattern;
  BlockCholesky factor;
  FrameSystem system;
};
// Factors K over every DOF in 6 × 6 node blocks (solver/block_cholesky.h: 3–4× CHOLMOD's
// simplicial factor on these frames, the same bits on every machine). reuse (optional): kept
// across calls; a frame with the previous call's members and supports then keeps K's pattern
// and the factor's symbolic analysis.
Status SolveFrame(const FrameModel& model, FrameResult* result, FrameWorkspace* reuse = nullptr);

}  // namespace pqlayout
