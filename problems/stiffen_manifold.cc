#include "problems/stiffen_manifold.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>

#include "problems/residuals/signed_planarity_residual.h"
#include "solver/cholmod_solver.h"

namespace pqlayout {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kActiveBand = 0.02;        // δ ≥ (1 − band) δ_allowed counts as active
constexpr double kRetractTolerance = 0.05;  // a retraction is done at δ ≤ (1 + this) δ_allowed (< target)
constexpr double kRetractAim = 0.01;        // … and aims at (1 − this) δ_allowed
constexpr int kRetractions = 20;            // Gauss–Newton steps at most
constexpr double kRegularisation = 1e-10;   // × the diagonal of J Jᵀ, for the projection
// × the diagonal of J Jᵀ (Marquardt's scaling, so that a small face is not damped more than
// a large one), for the retraction's steps: the sub-quads of an n-gon (n > 4) are nearly
// dependent (n − 3 conditions, n(n−1)(n−2)(n−3)/24 sub-quads), and undamped their Gram
// matrix turns a violation of 1e-3 into a step of decimetres.
constexpr double kDamping = 1e-3;
constexpr size_t kCache = 4;                // Ceres' line search returns to its base point

}  // namespace

struct PlanarityManifold::Linearisation {
  std::vector<double> z;
  std::vector<int> rows;                 // constraint indices (into constraints_)
  Eigen::SparseMatrix<double> J;         // rows × N, rows signed
  std::unique_ptr<CholmodSolver> gram;   // J Jᵀ + ε I
  mutable std::vector<double> tangent_gradient;  // P g at z, once computed (Plus)
};

PlanarityManifold::PlanarityManifold(const StiffenProblem& P, const BoxVariables& box, double allowed)
    : P_(P), box_(box), delta_(SignedPlanarityResidual::Create()) {
  for (size_t k = 0; k < P.sub_quads.size(); ++k) {
    const auto& s = P.sub_quads[k];
    if (box.FreeIndex(s[0]) >= 0 || box.FreeIndex(s[1]) >= 0 || box.FreeIndex(s[2]) >= 0 || box.FreeIndex(s[3]) >= 0)
      constraints_.push_back(static_cast<int>(k));
  }
  allowed_.assign(constraints_.size(), allowed);
}

int PlanarityManifold::AdmitStart(const double* z) {
  const std::vector<double> values = Values(z);
  int raised = 0;
  for (size_t r = 0; r < values.size(); ++r)
    if (std::abs(values[r]) > allowed_[r]) allowed_[r] = std::abs(values[r]), ++raised;
  cache_.clear();  // their active sets were found with the old allowances
  return raised;
}

PlanarityManifold::~PlanarityManifold() = default;

std::vector<double> PlanarityManifold::Values(const double* z) const {
  const std::vector<Vec3> x = World(P_, box_.Local(z));
  std::vector<double> values(constraints_.size());
  for (size_t r = 0; r < constraints_.size(); ++r) {
    const auto& s = P_.sub_quads[constraints_[r]];
    const double* points[4] = {x[s[0]].data(), x[s[1]].data(), x[s[2]].data(), x[s[3]].data()};
    delta_->Evaluate(points, &values[r], nullptr);
  }
  return values;
}

// See the header.
std::unique_ptr<PlanarityManifold::Linearisation> PlanarityManifold::Linearise(
    const std::vector<Vec3>& x, const std::vector<int>& rows, const std::vector<double>& values,
    const std::function<Vec3(int, int)>& dx, const std::vector<bool>* frozen, double regularisation) const {
  auto A = std::make_unique<Linearisation>();
  A->rows = rows;
  std::vector<Eigen::Triplet<double>> triplets;
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& s = P_.sub_quads[constraints_[rows[i]]];
    const double* points[4] = {x[s[0]].data(), x[s[1]].data(), x[s[2]].data(), x[s[3]].data()};
    std::array<double, 12> g{};
    double* jacobians[4] = {&g[0], &g[3], &g[6], &g[9]};
    double value;
    delta_->Evaluate(points, &value, jacobians);
    const double sign = values[rows[i]] < 0.0 ? -1.0 : 1.0;
    for (int j = 0; j < 4; ++j) {
      const int k = box_.FreeIndex(s[j]);
      if (k < 0) continue;
      for (int c = 0; c < 3; ++c)
        if (frozen == nullptr || !(*frozen)[3 * k + c])
          triplets.emplace_back(static_cast<int>(i), 3 * k + c, sign * Vec3(&g[3 * j]).dot(dx(k, c)));
    }
  }
  A->J.resize(static_cast<int>(rows.size()), box_.size());
  A->J.setFromTriplets(triplets.begin(), triplets.end());
  if (rows.empty()) return A;
  Eigen::SparseMatrix<double> gram = A->J * A->J.transpose();
  gram = 0.5 * (gram + Eigen::SparseMatrix<double>(gram.transpose()));  // symmetric to the bit
  const double floor = 1e-12 * gram.diagonal().mean() + 1e-300;  // a row whose coordinates are all frozen
  for (int i = 0; i < gram.rows(); ++i) gram.coeffRef(i, i) += regularisation * gram.coeffRef(i, i) + floor;
  A->gram = std::make_unique<CholmodSolver>();
  if (!A->gram->Factorize(gram).ok()) A->gram.reset();
  return A;
}

// The active set at z: the cached one, or the constraints within the band, less those the
// gradient (when given) pulls inside.
const PlanarityManifold::Linearisation& PlanarityManifold::At(const double* z, const double* gradient) const {
  const size_t bytes = sizeof(double) * box_.size();
  if (gradient == nullptr)
    for (const auto& A : cache_)
      if (std::memcmp(A->z.data(), z, bytes) == 0) return *A;
  const std::vector<double> values = Values(z);
  std::vector<int> rows;
  for (size_t r = 0; r < values.size(); ++r)
    if (std::abs(values[r]) >= (1.0 - kActiveBand) * allowed_[r]) rows.push_back(static_cast<int>(r));
  const std::vector<Vec3> x = World(P_, box_.Local(z));
  const auto dz = [&](int k, int c) { return box_.Derivative(k, c, z); };
  auto A = Linearise(x, rows, values, dz, nullptr, kRegularisation);
  if (gradient != nullptr && A->gram != nullptr) {
    const Eigen::VectorXd Jg = A->J * Eigen::Map<const Eigen::VectorXd>(gradient, box_.size());
    Eigen::VectorXd y;
    if (A->gram->Solve(Jg, &y).ok()) {
      std::vector<int> kept;
      for (size_t i = 0; i < rows.size(); ++i)
        if (y[i] <= 0.0) kept.push_back(rows[i]);
      if (kept.size() < rows.size()) A = Linearise(x, kept, values, dz, nullptr, kRegularisation);
    }
  }
  A->z.assign(z, z + box_.size());
  cache_.erase(std::remove_if(cache_.begin(), cache_.end(),
                              [&](const auto& B) { return std::memcmp(B->z.data(), z, bytes) == 0; }),
               cache_.end());
  cache_.push_front(std::move(A));
  if (cache_.size() > kCache) cache_.pop_back();
  return *cache_.front();
}

void PlanarityManifold::Project(const Linearisation& A, const double* v, double* out) const {
  Eigen::Map<const Eigen::VectorXd> in(v, box_.size());
  Eigen::Map<Eigen::VectorXd> result(out, box_.size());
  result = in;
  if (A.gram == nullptr) return;
  Eigen::VectorXd y;
  if (A.gram->Solve(Eigen::VectorXd(A.J * in), &y).ok()) result -= A.J.transpose() * y;
}

bool PlanarityManifold::Plus(const double* z, const double* delta, double* z_plus_delta) const {
  const Linearisation& A = At(z, nullptr);
  // Ceres' line-search minimiser also calls Plus(z, −g) with its tangent gradient g, only to
  // measure its gradient test; g can be far longer than any step, so that point need not be
  // feasible. Every other step whose retraction fails is refused (the line search shortens it).
  bool gradient_test = !A.tangent_gradient.empty();
  for (int i = 0; i < box_.size() && gradient_test; ++i) gradient_test = delta[i] == -A.tangent_gradient[i];
  Project(A, delta, z_plus_delta);
  for (int i = 0; i < box_.size(); ++i) z_plus_delta[i] += z[i];
  if (Retract(z_plus_delta) || gradient_test) return true;
  ++incomplete_retractions_;
  return false;
}

bool PlanarityManifold::RightMultiplyByPlusJacobian(const double* z, int num_rows, const double* ambient,
                                                    double* tangent) const {
  for (int r = 0; r < num_rows; ++r) {  // P is symmetric: (g P) = P g per row
    const Linearisation& A = At(z, ambient + r * box_.size());
    Project(A, ambient + r * box_.size(), tangent + r * box_.size());
    if (num_rows == 1) A.tangent_gradient.assign(tangent, tangent + box_.size());
  }
  return true;
}

bool PlanarityManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  for (int i = 0; i < box_.size(); ++i) y_minus_x[i] = y[i] - x[i];
  return true;
}

// Gauss–Newton in the local coordinates q (metres, not angles: at a box end ∂x/∂z vanishes
// and steps in z overshoot), on the violated sub-quads and those within the active band (all
// aimed at (1 − aim) δ_allowed, so that a fixed face does not push its neighbour out), the
// step clamped to the box; a coordinate at its bound that the step pushes outward is frozen
// (its column dropped) and the step recomputed.
bool PlanarityManifold::Retract(double* z) const {
  std::vector<Vec3> q = box_.Local(z);
  const int n = box_.size();
  const auto dq = [&](int k, int c) { return Vec3(P_.frames[box_.free()[k]].rotation.col(c)); };
  const auto bound = [&](int k, bool upper) { return upper ? P_.upper[box_.free()[k / 3]][k % 3] : P_.lower[box_.free()[k / 3]][k % 3]; };
  for (int iteration = 0;; ++iteration) {
    const std::vector<double> z_now = box_.Parameters(q);
    const std::vector<double> values = Values(z_now.data());
    std::vector<int> rows;
    bool violated = false;
    for (size_t r = 0; r < values.size(); ++r) {
      violated = violated || std::abs(values[r]) - allowed_[r] > kRetractTolerance * allowed_[r];
      if (std::abs(values[r]) >= (1.0 - kActiveBand) * allowed_[r]) rows.push_back(static_cast<int>(r));
    }
    if (!violated) break;
    if (iteration == kRetractions) return false;
    Eigen::VectorXd c(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) c[i] = std::abs(values[rows[i]]) - (1.0 - kRetractAim) * allowed_[rows[i]];
    const std::vector<Vec3> x = World(P_, q);
    std::vector<bool> frozen(n, false);
    Eigen::VectorXd step;
    for (int pass = 0; pass < 2; ++pass) {
      const auto A = Linearise(x, rows, values, dq, &frozen, kDamping);
      Eigen::VectorXd y;
      if (A->gram == nullptr || !A->gram->Solve(c, &y).ok()) return false;
      step = A->J.transpose() * y;  // q ← q − step
      bool refreeze = false;
      for (int k = 0; k < n && pass == 0; ++k) {
        const double value = q[box_.free()[k / 3]][k % 3];
        if ((value <= bound(k, false) && step[k] > 0.0) || (value >= bound(k, true) && step[k] < 0.0))
          frozen[k] = refreeze = true;
      }
      if (!refreeze) break;
    }
    for (int k = 0; k < n; ++k) {
      double& value = q[box_.free()[k / 3]][k % 3];
      value = std::clamp(value - step[k], bound(k, false), bound(k, true));
    }
  }
  const std::vector<double> result = box_.Parameters(q);
  std::copy(result.begin(), result.end(), z);
  return true;
}

int PlanarityManifold::active() const { return cache_.empty() ? 0 : static_cast<int>(cache_.front()->rows.size()); }

}  // namespace pqlayout
