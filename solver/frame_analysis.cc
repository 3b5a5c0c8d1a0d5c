#include "solver/frame_analysis.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/SparseCore>

#include "solver/block_cholesky.h"

namespace pqlayout {

FrameSection FrameSection::CircularHollow(double D, double t) {
  const double d = D - 2.0 * t;
  FrameSection s;
  s.area = M_PI / 4.0 * (D * D - d * d);
  s.inertia_y = s.inertia_z = M_PI / 64.0 * (std::pow(D, 4) - std::pow(d, 4));
  s.torsion = 2.0 * s.inertia_y;
  return s;
}

FrameSection FrameSection::RectangularHollow(double b, double h, double t) {
  FrameSection s;
  const double bi = b - 2.0 * t, hi = h - 2.0 * t;
  s.area = b * h - bi * hi;
  s.inertia_y = (b * h * h * h - bi * hi * hi * hi) / 12.0;  // deflection along z (height)
  s.inertia_z = (h * b * b * b - hi * bi * bi * bi) / 12.0;
  s.torsion = 2.0 * t * std::pow(b - t, 2) * std::pow(h - t, 2) / (b + h - 2.0 * t);
  return s;
}

const char* DofName(int dof) {
  static const char* kNames[6] = {"u_x", "u_y", "u_z", "θ_x", "θ_y", "θ_z"};
  return kNames[dof];
}

namespace {

Eigen::Matrix<double, 12, 12> Transformation(const Eigen::Matrix3d& R) {
  Eigen::Matrix<double, 12, 12> T = Eigen::Matrix<double, 12, 12>::Zero();
  for (int k = 0; k < 4; ++k) T.block<3, 3>(3 * k, 3 * k) = R;
  return T;
}

Status CheckModel(const FrameModel& m) {
  const int n = static_cast<int>(m.nodes.size());
  if (n == 0 || m.members.empty()) return Status::InvalidInput("frame: no nodes or no members");
  if (!m.restraints.empty() && static_cast<int>(m.restraints.size()) != n)
    return Status::Internal("frame: restraints size mismatch");
  if (!m.loads.empty() && static_cast<int>(m.loads.size()) != n) return Status::Internal("frame: loads size mismatch");
  if (!(m.section.area > 0 && m.section.inertia_y > 0 && m.section.inertia_z > 0 && m.section.torsion > 0))
    return Status::InvalidInput("frame: section constants must be positive");
  for (size_t e = 0; e < m.members.size(); ++e) {
    const auto& mb = m.members[e];
    if (mb.a < 0 || mb.b < 0 || mb.a >= n || mb.b >= n || mb.a == mb.b)
      return Status::InvalidInput("frame: member " + std::to_string(e) + " has invalid end nodes");
    if (!((m.nodes[mb.a] - m.nodes[mb.b]).norm() > 0.0))
      return Status::InvalidInput("frame: member " + std::to_string(e) + " has zero length");
  }
  return Status::Ok();
}

}  // namespace

namespace {

// The topology a FramePattern is made for: node count, numbering, members' ends, restraints.
std::vector<int> Topology(const FrameModel& m, bool every_dof) {
  std::vector<int> t{static_cast<int>(m.nodes.size()), every_dof ? 1 : 0, static_cast<int>(m.restraints.size())};
  for (const auto& mb : m.members) t.push_back(mb.a), t.push_back(mb.b);
  for (const auto& r : m.restraints) {
    int bits = 0;
    for (int d = 0; d < 6; ++d) bits |= (r[d] ? 1 : 0) << d;
    t.push_back(bits);
  }
  return t;
}

// The slot of (row, column) in K's compressed columns.
int Slot(const Eigen::SparseMatrix<double>& K, int row, int column) {
  const int* begin = K.innerIndexPtr() + K.outerIndexPtr()[column];
  const int* end = K.innerIndexPtr() + K.outerIndexPtr()[column + 1];
  return static_cast<int>(std::lower_bound(begin, end, row) - K.innerIndexPtr());
}

// Whether K is compressed, size × size, with the pattern's structure (its values then only need
// writing).
bool HasPattern(const Eigen::SparseMatrix<double>& K, int size, const FramePattern& pattern) {
  return K.isCompressed() && K.rows() == size && K.cols() == size &&
         static_cast<size_t>(K.nonZeros()) == pattern.inner.size() && pattern.outer.size() == static_cast<size_t>(size) + 1 &&
         std::equal(pattern.outer.begin(), pattern.outer.end(), K.outerIndexPtr()) &&
         std::equal(pattern.inner.begin(), pattern.inner.end(), K.innerIndexPtr());
}

}  // namespace

Status AssembleFrame(const FrameModel& m, FrameSystem* s, bool every_dof, FramePattern* pattern) {
  PQ_RETURN_IF_ERROR(CheckModel(m));
  const int n = static_cast<int>(m.nodes.size());
  s->index.assign(6 * n, -1);
  s->free = 0;
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 6; ++d)
      if (m.restraints.empty() || !m.restraints[i][d]) s->index[6 * i + d] = s->free++;
  // The row and column of DOF k in K: its free number, or k itself over every DOF (−1: left out).
  const auto place = [&](int k) { return s->index[k] < 0 ? -1 : every_dof ? k : s->index[k]; };
  const int size = every_dof ? 6 * n : s->free;
  std::vector<int> topology;
  if (pattern != nullptr) topology = Topology(m, every_dof);
  const bool cached = pattern != nullptr && topology == pattern->ends;
  std::vector<Eigen::Triplet<double>> triplets;
  double* values = nullptr;  // the cached path: K's values, a slot's first term stored, later ones added
                             // (setFromTriplets' order)
  if (cached) {
    if (!HasPattern(s->K, size, *pattern))
      s->K = Eigen::Map<const Eigen::SparseMatrix<double>>(size, size, static_cast<int>(pattern->inner.size()),
                                                           pattern->outer.data(), pattern->inner.data(),
                                                           std::vector<double>(pattern->inner.size()).data());
    values = s->K.valuePtr();
    std::fill(values, values + s->K.nonZeros(), 0.0);
    pattern->added.assign(pattern->inner.size(), 0);
  } else {
    triplets.reserve(144 * m.members.size() + (every_dof ? 6 * n : 0));
  }
  double diagonal_max = 0.0;
  s->member_k.resize(m.members.size()), s->member_t.resize(m.members.size());
  for (size_t e = 0; e < m.members.size(); ++e) {
    const auto& mb = m.members[e];
    const double L = (m.nodes[mb.b] - m.nodes[mb.a]).norm();
    s->member_t[e] = Transformation(MemberFrame<double>(m.nodes[mb.a], m.nodes[mb.b], mb.up));
    s->member_k[e] = LocalBeamStiffness<double>(L, m.section, m.material);
    const Eigen::Matrix<double, 12, 12> K = s->member_t[e].transpose() * s->member_k[e] * s->member_t[e];
    int dofs[12];
    for (int k = 0; k < 6; ++k) dofs[k] = place(6 * mb.a + k), dofs[6 + k] = place(6 * mb.b + k);
    for (int p = 0; p < 12; ++p)
      for (int q = 0; q < 12; ++q) {
        if (dofs[p] < 0 || dofs[q] < 0) continue;
        if (!cached) {
          triplets.emplace_back(dofs[p], dofs[q], K(p, q));
          continue;
        }
        const int slot = pattern->slots[144 * e + 12 * p + q];
        values[slot] = pattern->added[slot] ? values[slot] + K(p, q) : K(p, q);
        pattern->added[slot] = 1;
      }
    diagonal_max = std::max(diagonal_max, K.diagonal().cwiseAbs().maxCoeff());
  }
  // Over every DOF, a restrained one is its own row: the identity at the members' largest
  // diagonal entry (it then neither moves nor sets the factor's condition estimate).
  if (cached) {
    for (const int slot : pattern->restrained) values[slot] = diagonal_max;
    return Status::Ok();
  }
  if (every_dof)
    for (int k = 0; k < 6 * n; ++k)
      if (s->index[k] < 0) triplets.emplace_back(k, k, diagonal_max);
  s->K.resize(size, size);
  s->K.setFromTriplets(triplets.begin(), triplets.end());
  if (pattern == nullptr) return Status::Ok();
  // The pattern for the next call with this topology.
  pattern->ends = std::move(topology);
  pattern->outer.assign(s->K.outerIndexPtr(), s->K.outerIndexPtr() + size + 1);
  pattern->inner.assign(s->K.innerIndexPtr(), s->K.innerIndexPtr() + s->K.nonZeros());
  pattern->slots.assign(144 * m.members.size(), -1);
  for (size_t e = 0; e < m.members.size(); ++e) {
    int dofs[12];
    for (int k = 0; k < 6; ++k) dofs[k] = place(6 * m.members[e].a + k), dofs[6 + k] = place(6 * m.members[e].b + k);
    for (int p = 0; p < 12; ++p)
      for (int q = 0; q < 12; ++q)
        if (dofs[p] >= 0 && dofs[q] >= 0) pattern->slots[144 * e + 12 * p + q] = Slot(s->K, dofs[p], dofs[q]);
  }
  pattern->restrained.clear();
  if (every_dof)
    for (int k = 0; k < 6 * n; ++k)
      if (s->index[k] < 0) pattern->restrained.push_back(Slot(s->K, k, k));
  return Status::Ok();
}

Status SolveFrame(const FrameModel& m, FrameResult* r, FrameWorkspace* reuse) {
  FrameSystem own_system;
  FrameSystem& system = reuse != nullptr ? reuse->system : own_system;
  PQ_RETURN_IF_ERROR(AssembleFrame(m, &system, true, reuse != nullptr ? &reuse->pattern : nullptr));
  const int n = static_cast<int>(m.nodes.size());
  const std::vector<int>& index = system.index;
  const auto& member_k = system.member_k;
  const auto& member_t = system.member_t;
  Eigen::VectorXd f_full = Eigen::VectorXd::Zero(6 * n);
  for (int i = 0; i < n && !m.loads.empty(); ++i) f_full.segment<6>(6 * i) = m.loads[i];
  Eigen::VectorXd f = f_full;  // a load on a restrained DOF goes to the support: its row is the identity
  for (int k = 0; k < 6 * n; ++k)
    if (index[k] < 0) f[k] = 0.0;

  BlockCholesky own;
  BlockCholesky& solver = reuse != nullptr ? reuse->factor : own;
  const Status factored = solver.Factorize(system.K);
  auto unsupported = [&](int row, bool whole_node, const std::string& why) {
    return Status::InvalidInput("the frame is a mechanism (" + why + "): node " + std::to_string(row / 6) + " (" +
                                (whole_node ? "?" : DofName(row % 6)) +
                                ") belongs to a part that the supports do not hold; check boundary.default / boundary.rules");
  };
  if (!factored.ok()) {
    if (factored.code() == StatusCode::kInternal && solver.failed_row() >= 0)
      return unsupported(solver.failed_row(), true, "singular stiffness");
    return factored;
  }
  Eigen::VectorXd u;
  PQ_RETURN_IF_ERROR(solver.Solve(f, &u));
  if (solver.rcond() < 1e-13 || !u.allFinite()) {
    // Nearly singular: report the DOF that moves most.
    int row = 0;
    u.cwiseAbs().maxCoeff(&row);
    std::ostringstream why;
    why << "reciprocal condition number " << solver.rcond();
    return unsupported(row, false, why.str());
  }

  // Reactions: what the supports must add so that K u = f + R holds at every DOF.
  Eigen::VectorXd internal = Eigen::VectorXd::Zero(6 * n);
  r->member_end_forces.resize(m.members.size());
  r->axial_force.resize(m.members.size());
  for (size_t e = 0; e < m.members.size(); ++e) {
    const auto& mb = m.members[e];
    Eigen::Matrix<double, 12, 1> ue;
    ue << u.segment<6>(6 * mb.a), u.segment<6>(6 * mb.b);
    const Eigen::Matrix<double, 12, 1> local = member_k[e] * (member_t[e] * ue);
    r->member_end_forces[e] = local;
    r->axial_force[e] = local[6];  // force at end b along local x: tension positive
    const Eigen::Matrix<double, 12, 1> global = member_t[e].transpose() * local;
    internal.segment<6>(6 * mb.a) += global.head<6>();
    internal.segment<6>(6 * mb.b) += global.tail<6>();
  }
  r->displacement.resize(n);
  r->reaction.assign(n, NodeVector::Zero());
  r->nodal_compliance.resize(n);
  for (int i = 0; i < n; ++i) {
    r->displacement[i] = u.segment<6>(6 * i);
    for (int d = 0; d < 6; ++d)
      if (index[6 * i + d] < 0) r->reaction[i][d] = internal[6 * i + d] - f_full[6 * i + d];
    r->nodal_compliance[i] = f_full.segment<3>(6 * i).dot(u.segment<3>(6 * i));
  }
  r->compliance = f_full.dot(u);
  return Status::Ok();
}

}  // namespace pqlayout
