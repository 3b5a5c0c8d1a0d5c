#include "solver/cholmod_solver.h"

#include <cholmod.h>

#include <cmath>
#include <algorithm>
#include <string>
#include <vector>

#include "solver/nested_dissection.h"
#include "solver/numerics.h"

namespace pqlayout {

struct CholmodSolver::Impl {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  std::vector<int> pattern_outer, pattern_inner;  // sparsity pattern the factor was analysed for
  std::vector<int> ordering;                      // SetOrdering's, or empty
  double lnz = 0.0, flops = 0.0;                  // of the last analysis
  Impl() {
    cholmod_start(&common);
    // One thread (the default): simplicial LLᵀ, CHOLMOD's own loops, no BLAS, so the factor
    // is bit-identical on every CPU (solver/numerics.h). The supernodal factor calls OpenBLAS,
    // whose kernels differ per CPU by an ulp, and the non-convex stages downstream amplify
    // that into another layout; it is ~5x faster at 500k unknowns, so `threads` > 1, which
    // gives up bit-identity anyway, lets CHOLMOD choose it.
    common.supernodal = NumericThreads() > 1 ? CHOLMOD_AUTO : CHOLMOD_SIMPLICIAL;
    common.final_ll = true;  // LLᵀ: a non-positive pivot is refused (LDLᵀ would go on past it)
    common.print = 0;  // no printing from inside CHOLMOD; errors come back as Status
    common.error_handler = nullptr;
  }
  ~Impl() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>()) {}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::factorized() const { return impl_->factor != nullptr; }
bool CholmodSolver::is_supernodal() const { return impl_->factor && impl_->factor->is_super; }
double CholmodSolver::factor_nonzeros() const { return impl_->lnz; }
double CholmodSolver::factor_flops() const { return impl_->flops; }
void CholmodSolver::SetOrdering(std::vector<int> perm) { impl_->ordering = std::move(perm); }

// The symbolic analysis of A (n rows) into impl_->factor: CHOLMOD's own ordering, or the one
// given by SetOrdering (then alone; CHOLMOD postorders its elimination tree, which keeps the fill).
Status CholmodSolver::Analyze(cholmod_sparse* A, long n) {
  cholmod_common* c = &impl_->common;
  const std::vector<int>& perm = impl_->ordering;
  if (perm.empty()) {
    impl_->factor = cholmod_analyze(A, c);
  } else {
    if (!IsPermutation(perm, n))
      return Status::InvalidInput("the ordering given is not a permutation of the matrix's " + std::to_string(n) +
                                  " rows");
    const int methods = c->nmethods, method = c->method[0].ordering;
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_GIVEN;
    impl_->factor = cholmod_analyze_p(A, const_cast<int*>(perm.data()), nullptr, 0, c);
    c->nmethods = methods;
    c->method[0].ordering = method;
  }
  impl_->lnz = c->lnz;
  impl_->flops = c->fl;
  return Status::Ok();
}

Status CholmodSolver::Factorize(const Eigen::SparseMatrix<double>& A_in, bool reuse_analysis) {
  // The previous factor's symbolic analysis (ordering, elimination tree) is kept only for
  // the same sparsity pattern; cholmod_factorize then redoes the numbers alone.
  cholmod_factor* previous = impl_->factor;
  impl_->factor = nullptr;
  struct FreeUnused {  // the previous factor, unless it is reused below
    cholmod_factor** factor;
    cholmod_common* common;
    ~FreeUnused() {
      if (*factor) cholmod_free_factor(factor, common);
    }
  } free_unused{&previous, &impl_->common};
  rows_ = 0;
  failed_row_ = -1;
  rcond_ = 0.0;
  if (A_in.rows() != A_in.cols())
    return Status::InvalidInput("matrix is not square (" + std::to_string(A_in.rows()) + " x " +
                                std::to_string(A_in.cols()) + ")");
  if (A_in.rows() == 0) return Status::InvalidInput("matrix is empty");
  Eigen::SparseMatrix<double> A = A_in;
  A.makeCompressed();
  for (int k = 0; k < A.nonZeros(); ++k)
    if (!std::isfinite(A.valuePtr()[k])) return Status::InvalidInput("matrix has a non-finite entry");
  const double asymmetry = (Eigen::SparseMatrix<double>(A.transpose()) - A).cwiseAbs().sum();
  if (!(asymmetry <= 1e-12 * A.cwiseAbs().sum()))
    return Status::InvalidInput("matrix is not symmetric (relative asymmetry " + std::to_string(asymmetry) + ")");

  cholmod_sparse view{};
  view.nrow = view.ncol = A.rows();
  view.nzmax = A.nonZeros();
  view.p = A.outerIndexPtr();
  view.i = A.innerIndexPtr();
  view.x = A.valuePtr();
  view.stype = -1;  // symmetric, use the lower triangle
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;

  cholmod_common* c = &impl_->common;
  const bool same_pattern =
      reuse_analysis && previous != nullptr &&
      impl_->pattern_outer.size() == static_cast<size_t>(A.outerSize() + 1) &&
      impl_->pattern_inner.size() == static_cast<size_t>(A.nonZeros()) &&
      std::equal(impl_->pattern_outer.begin(), impl_->pattern_outer.end(), A.outerIndexPtr()) &&
      std::equal(impl_->pattern_inner.begin(), impl_->pattern_inner.end(), A.innerIndexPtr());
  if (same_pattern) {
    impl_->factor = previous;
    previous = nullptr;
  } else {
    PQ_RETURN_IF_ERROR(Analyze(&view, A.rows()));
    impl_->pattern_outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
    impl_->pattern_inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  }
  if (!impl_->factor) return Status::Internal("CHOLMOD analyze failed (status " + std::to_string(c->status) + ")");
  cholmod_factorize(&view, impl_->factor, c);
  if (c->status == CHOLMOD_NOT_POSDEF || impl_->factor->minor < impl_->factor->n) {
    const auto column = impl_->factor->minor;
    // minor counts in the fill-reducing ordering; Perm maps it back to A's numbering.
    const auto* perm = static_cast<const int*>(impl_->factor->Perm);
    failed_row_ = perm && column < impl_->factor->n ? perm[column] : static_cast<int>(column);
    cholmod_free_factor(&impl_->factor, c);
    return Status::Internal("matrix is not positive definite (Cholesky failed at row " +
                            std::to_string(failed_row_) + ")");
  }
  if (c->status != CHOLMOD_OK) {
    cholmod_free_factor(&impl_->factor, c);
    return Status::Internal("CHOLMOD factorize failed (status " + std::to_string(c->status) + ")");
  }
  rows_ = static_cast<int>(A.rows());
  rcond_ = cholmod_rcond(impl_->factor, c);
  return Status::Ok();
}

Status CholmodSolver::Solve(const Eigen::MatrixXd& b, Eigen::MatrixXd* x) const {
  if (!impl_->factor) return Status::Internal("Solve called without a successful Factorize");
  if (b.rows() != rows_)
    return Status::Internal("right-hand side has " + std::to_string(b.rows()) + " rows, expected " +
                            std::to_string(rows_));
  cholmod_dense rhs{};
  rhs.nrow = b.rows();
  rhs.ncol = b.cols();
  rhs.nzmax = b.size();
  rhs.d = b.rows();
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_common* c = &impl_->common;
  cholmod_dense* sol = cholmod_solve(CHOLMOD_A, impl_->factor, &rhs, c);
  if (!sol) return Status::Internal("CHOLMOD solve failed (status " + std::to_string(c->status) + ")");
  *x = Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(sol->x), b.rows(), b.cols());
  cholmod_free_dense(&sol, c);
  return Status::Ok();
}

Status CholmodSolver::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
  Eigen::MatrixXd solution;
  PQ_RETURN_IF_ERROR(Solve(Eigen::MatrixXd(b), &solution));
  *x = solution.col(0);
  return Status::Ok();
}

}  // namespace pqlayout
