#include "solver/frame_buckling.h"

#include <Spectra/SymGEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "solver/cholmod_solver.h"

namespace pqlayout {
namespace {

constexpr double kNoCompression = 1e-9;  // largest compression below this × max |N|: no buckling
constexpr int kMinSubspace = 20;         // Lanczos subspace (ncv) at least, ≥ 2 nev + 1
constexpr int kMaxRestarts = 1000;
constexpr double kTolerance = 1e-10;     // Spectra's relative eigenvalue tolerance

// y = A x for a symmetric sparse A stored whole (Spectra's OpType).
struct SparseProduct {
  using Scalar = double;
  const Eigen::SparseMatrix<double>& A;
  Eigen::Index rows() const { return A.rows(); }
  Eigen::Index cols() const { return A.cols(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, A.rows()) = A * Eigen::Map<const Eigen::VectorXd>(x, A.cols());
  }
};

// B = K: products and solves, the solves by CHOLMOD (Spectra's BOpType in regular-inverse mode).
struct StiffnessOperator {
  using Scalar = double;
  const Eigen::SparseMatrix<double>& K;
  const CholmodSolver& solver;
  mutable int solves = 0;
  mutable bool failed = false;
  Eigen::Index rows() const { return K.rows(); }
  Eigen::Index cols() const { return K.cols(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, K.rows()) = K * Eigen::Map<const Eigen::VectorXd>(x, K.cols());
  }
  void solve(const double* x, double* y) const {
    Eigen::VectorXd out;
    ++solves;
    if (!solver.Solve(Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(x, K.rows())), &out).ok()) {
      failed = true;
      out = Eigen::VectorXd::Zero(K.rows());
    }
    Eigen::Map<Eigen::VectorXd>(y, K.rows()) = out;
  }
};

// −K_G over the free DOFs.
Eigen::SparseMatrix<double> NegativeGeometricStiffness(const FrameModel& m, const FrameSystem& s,
                                                       const std::vector<double>& axial) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(144 * m.members.size());
  for (size_t e = 0; e < m.members.size(); ++e) {
    const auto& mb = m.members[e];
    const double L = (m.nodes[mb.b] - m.nodes[mb.a]).norm();
    const Matrix12<double> G =
        s.member_t[e].transpose() * LocalGeometricStiffness(L, axial[e], m.section) * s.member_t[e];
    int dofs[12];
    for (int k = 0; k < 6; ++k) dofs[k] = 6 * mb.a + k, dofs[6 + k] = 6 * mb.b + k;
    for (int p = 0; p < 12; ++p)
      for (int q = 0; q < 12; ++q)
        if (s.index[dofs[p]] >= 0 && s.index[dofs[q]] >= 0) triplets.emplace_back(s.index[dofs[p]], s.index[dofs[q]], -G(p, q));
  }
  Eigen::SparseMatrix<double> A(s.free, s.free);
  A.setFromTriplets(triplets.begin(), triplets.end());
  return A;
}

// φ over the free DOFs → per node, max |translation| = 1, its largest component positive.
std::vector<NodeVector> ModeShape(const FrameSystem& s, const Eigen::VectorXd& phi) {
  const int n = static_cast<int>(s.index.size()) / 6;
  std::vector<NodeVector> mode(n, NodeVector::Zero());
  for (int k = 0; k < 6 * n; ++k)
    if (s.index[k] >= 0) mode[k / 6][k % 6] = phi[s.index[k]];
  double largest = 0.0, sign = 1.0, component = 0.0;
  for (const auto& v : mode) {
    largest = std::max(largest, v.head<3>().norm());
    for (int d = 0; d < 3; ++d)
      if (std::abs(v[d]) > component) component = std::abs(v[d]), sign = v[d] > 0.0 ? 1.0 : -1.0;
  }
  if (largest > 0.0)
    for (auto& v : mode) v *= sign / largest;
  return mode;
}

}  // namespace

Status SolveBuckling(const FrameModel& m, const FrameResult& linear, int modes, BucklingResult* r) {
  *r = BucklingResult();
  if (linear.axial_force.size() != m.members.size()) return Status::Internal("buckling: no linear solution");
  double largest = 0.0, compression = 0.0;
  for (const double N : linear.axial_force) largest = std::max(largest, std::abs(N)), compression = std::max(compression, -N);
  if (!(compression > kNoCompression * largest)) return Status::Ok();  // tension only: no buckling under this load
  FrameSystem s;
  PQ_RETURN_IF_ERROR(AssembleFrame(m, &s));
  if (s.free < 3) return Status::Ok();
  const Eigen::SparseMatrix<double> A = NegativeGeometricStiffness(m, s, linear.axial_force);
  CholmodSolver solver;
  PQ_RETURN_IF_ERROR(solver.Factorize(s.K).WithContext("buckling"));
  const int nev = std::clamp(modes, 1, s.free - 2);
  const int ncv = std::min(s.free, std::max(2 * nev + 1, kMinSubspace));
  SparseProduct op{A};
  StiffnessOperator bop{s.K, solver};
  Spectra::SymGEigsSolver<SparseProduct, StiffnessOperator, Spectra::GEigsMode::RegularInverse> eigs(op, bop, nev, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, kMaxRestarts, kTolerance);
  r->operations = bop.solves;
  if (bop.failed) return Status::Internal("buckling: a CHOLMOD solve failed");
  if (eigs.info() != Spectra::CompInfo::Successful)
    return Status::Internal("buckling: the Lanczos iteration did not converge (" + std::to_string(bop.solves) + " solves)");
  const Eigen::VectorXd mu = eigs.eigenvalues();  // largest first
  const Eigen::MatrixXd phi = eigs.eigenvectors();
  for (int i = 0; i < mu.size(); ++i) {
    if (!(mu[i] > 0.0) || !std::isfinite(1.0 / mu[i])) continue;
    r->factors.push_back(1.0 / mu[i]);
    r->modes.push_back(ModeShape(s, phi.col(i)));
  }
  r->buckles = !r->factors.empty();
  return Status::Ok();
}

namespace {

template <typename T>
void AppendBytes(std::string* key, const T& value) {
  key->append(reinterpret_cast<const char*>(&value), sizeof(T));
}

// The inputs of SolveBuckling as bytes (everything it reads: the loads only through N).
std::string BucklingKey(const FrameModel& m, const FrameResult& linear, int modes) {
  std::string key;
  AppendBytes(&key, modes);
  AppendBytes(&key, m.nodes.size());
  for (const auto& p : m.nodes) AppendBytes(&key, p);
  AppendBytes(&key, m.members.size());
  for (const auto& member : m.members) AppendBytes(&key, member.a), AppendBytes(&key, member.b), AppendBytes(&key, member.up);
  AppendBytes(&key, m.restraints.size());
  for (const auto& r : m.restraints)
    for (const bool fixed : r) AppendBytes(&key, fixed);
  AppendBytes(&key, m.section.area), AppendBytes(&key, m.section.inertia_y), AppendBytes(&key, m.section.inertia_z);
  AppendBytes(&key, m.section.torsion);
  AppendBytes(&key, m.material.youngs_modulus), AppendBytes(&key, m.material.shear_modulus);
  AppendBytes(&key, linear.axial_force.size());
  for (const double n : linear.axial_force) AppendBytes(&key, n);
  return key;
}

}  // namespace

Status BucklingMemo::Solve(const FrameModel& model, const FrameResult& linear, int modes, BucklingResult* result,
                           bool* reused) {
  std::string key = BucklingKey(model, linear, modes);
  *reused = !key_.empty() && key == key_;
  if (*reused) {
    *result = result_;
    return Status::Ok();
  }
  key_.clear();
  PQ_RETURN_IF_ERROR(SolveBuckling(model, linear, modes, result));
  key_ = std::move(key);
  result_ = *result;
  return Status::Ok();
}

}  // namespace pqlayout
