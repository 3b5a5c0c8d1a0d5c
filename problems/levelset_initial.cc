// The level sets' initial guess (paper §3.1): oriented guidance, Poisson fits with seams, the smallest eigenvector, conjugate targets.
#include "problems/levelset_internal.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>

#include "geometry/differential_operators.h"
#include "problems/residuals/conjugacy_residual.h"
#include "solver/cholmod_solver.h"

namespace pqlayout {
namespace levelset_internal {

// ---- Initial guess -------------------------------------------------------------------

// n × d per face, with signs made consistent across neighbouring faces, strongest guidance
// first (a line field has no global orientation near its singularities; those regions are
// reached last and matter least).
std::vector<Eigen::Vector3d> OrientedCrossField(const SurfaceModel& s, const GuidanceField& g) {
  std::vector<Eigen::Vector3d> u(s.num_faces());
  for (int f = 0; f < s.num_faces(); ++f) u[f] = s.face_normal(f).cross(g.direction[f]);
  std::vector<char> done(s.num_faces(), 0);
  std::vector<int> by_weight(s.num_faces());
  std::iota(by_weight.begin(), by_weight.end(), 0);
  std::stable_sort(by_weight.begin(), by_weight.end(), [&](int a, int b) { return g.weight[a] > g.weight[b]; });
  using Item = std::pair<double, int>;
  for (const int seed : by_weight) {
    if (done[seed]) continue;
    std::priority_queue<Item> queue;
    queue.push({g.weight[seed], seed});
    done[seed] = 1;
    while (!queue.empty()) {
      const int f = queue.top().second;
      queue.pop();
      for (const auto n : s.mesh().ff_range(FaceHandle(f))) {
        if (done[n.idx()]) continue;
        done[n.idx()] = 1;
        if (u[n.idx()].dot(u[f]) < 0.0) u[n.idx()] = -u[n.idx()];
        queue.push({g.weight[n.idx()], n.idx()});
      }
    }
  }
  return u;
}

// Seams in the linear initial guess: how stiff the transitions u₊ = s·u₋ + a are against the
// gradient fit (a violation of 1/λ levels costs about as much as one level of gradient error
// over the vertex's area); the result is then made exact (ProjectTransitions). The Ceres
// solves need no such weight: there the transitions are exact by construction (Chart).
constexpr double kTransitionStiffness = 1e3;

// argmin_u Σ_f ω_f A_f |∇u_f − target_f|² + Σ_seam pairs λ A_v / h² (u₊ − s·u₋ − a_p)².
// Without seams one vertex per connected component is held at 0; with seams too, unless a
// seam of sign −1 already fixes the constant (offsets given). seams/family: the seams and
// which offsets (0 φ, 1 ψ) apply; free_offsets: the a_p are unknowns too, returned in the
// seams' offsets (not rounded), and offset_block (if given) gets the offsets' block of the
// system's inverse, (A⁻¹)_aa: how the fit's energy rises when they are moved (RoundOffsets).
Status PoissonFit(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<Eigen::Vector3d>& target, const std::vector<double>& omega, std::vector<double>* u, LevelSetSeams* seams, int family, bool free_offsets, double h,
                  Eigen::MatrixXd* offset_block) {
  std::vector<int> component;
  const int components = ConnectedComponents(s, &component);
  std::vector<char> anchored(components, 0);
  const bool has_seams = seams != nullptr && seams->cut != nullptr;
  std::vector<double>* offsets = has_seams ? (family == 0 ? &seams->phi_offset : &seams->psi_offset) : nullptr;
  if (has_seams && !free_offsets)  // a seam of sign −1 fixes the constant of its component
    for (const auto& pair : seams->cut->copy_pairs())
      if (seams->sign[pair.path] < 0) anchored[component[pair.minus]] = 1;
  std::vector<int> unknown(s.num_vertices(), -1);
  int n = 0;
  for (int v = 0; v < s.num_vertices(); ++v) {
    if (!anchored[component[v]]) anchored[component[v]] = 1;
    else unknown[v] = n++;
  }
  const int first_offset = n;
  if (has_seams && free_offsets) n += seams->cut->num_paths();
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    const double a = omega[f] * s.face_area(f);
    for (int p = 0; p < 3; ++p) {
      if (unknown[ids[p]] < 0) continue;
      rhs[unknown[ids[p]]] += a * geo.G[f].col(p).dot(target[f]);
      for (int q = 0; q < 3; ++q)
        if (unknown[ids[q]] >= 0)
          triplets.emplace_back(unknown[ids[p]], unknown[ids[q]], a * geo.G[f].col(p).dot(geo.G[f].col(q)));
    }
  }
  if (has_seams) {
    for (const auto& pair : seams->cut->copy_pairs()) {
      const double sign = seams->sign[pair.path];
      if (pair.minus == pair.plus && sign > 0) continue;  // the tip of a translation seam: no condition
      // r = Σ coef·x − constant
      std::vector<std::pair<int, double>> coef;
      if (pair.minus == pair.plus) coef.push_back({unknown[pair.minus], 1.0 - sign});
      else coef.push_back({unknown[pair.plus], 1.0}), coef.push_back({unknown[pair.minus], -sign});
      double constant = 0.0;
      if (free_offsets) coef.push_back({first_offset + pair.path, -1.0});
      else constant = (*offsets)[pair.path];
      const double weight = kTransitionStiffness * s.vertex_area(pair.minus) / (h * h);
      for (const auto& [i, ci] : coef) {
        if (i < 0) continue;
        rhs[i] += weight * constant * ci;
        for (const auto& [j, cj] : coef)
          if (j >= 0) triplets.emplace_back(i, j, weight * ci * cj);
      }
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  CholmodSolver solver;
  PQ_RETURN_IF_ERROR(solver.Factorize(A).WithContext("levelset initial guess"));
  Eigen::VectorXd x;
  PQ_RETURN_IF_ERROR(solver.Solve(rhs, &x).WithContext("levelset initial guess"));
  u->assign(s.num_vertices(), 0.0);
  for (int v = 0; v < s.num_vertices(); ++v)
    if (unknown[v] >= 0) (*u)[v] = x[unknown[v]];
  if (has_seams && free_offsets) {
    const int k = seams->cut->num_paths();
    for (int p = 0; p < k; ++p) (*offsets)[p] = x[first_offset + p];
    if (offset_block != nullptr && k > 0) {
      Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(n, k), solved;
      for (int p = 0; p < k; ++p) columns(first_offset + p, p) = 1.0;
      PQ_RETURN_IF_ERROR(solver.Solve(columns, &solved).WithContext("levelset initial guess"));
      *offset_block = solved.bottomRows(k);
    }
  }
  return Status::Ok();
}

// Offsets to whole levels; odd ones across sign −1 seams, so that the branch point (u = a/2
// there) lies half a level from every φ and ψ line, in the middle of a cell: that cell is a
// hexagon (the cone angle there is 3π), which extraction cuts into two quads, leaving two
// vertices where five quads meet. With even offsets the lines would run through the branch
// point, where P1 level lines of a cone point crowd and cross at small angles.
// Without `block` each offset goes to its nearest allowed value. With it (the offsets' block
// C = (A⁻¹)_aa of the free fit), the seams are rounded together: the fit's energy with the
// offsets held at a exceeds the free minimum a* by ½ (a − a*)ᵀ C⁻¹ (a − a*), and of the two
// nearest allowed values per seam the combination of least excess is taken (all 2^k up to
// kMaxJointSeams seams; beyond, single flips from the nearest while they help). Seams near a
// common singularity pull together: rounding them one by one (free ψ 10.13, 9.63, 9.64, 10.13
// → 11, 9, 9, 11 on the 112k Great Court) can shift the branch points against each other.
constexpr int kMaxJointSeams = 12;

void RoundOffsets(const LevelSetSeams& seams, std::vector<double>* offsets, const Eigen::MatrixXd* block) {
  const int k = static_cast<int>(offsets->size());
  Eigen::VectorXd free(k), low(k), rounded(k);
  for (int p = 0; p < k; ++p) {
    const double a = (*offsets)[p];
    free[p] = a;
    low[p] = seams.sign[p] < 0 ? 2.0 * std::floor((a - 1.0) / 2.0) + 1.0 : std::floor(a);
    const double step = seams.sign[p] < 0 ? 2.0 : 1.0;
    rounded[p] = a - low[p] <= 0.5 * step ? low[p] : low[p] + step;
  }
  if (block != nullptr && k > 0 && block->rows() == k) {
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(*block);
    auto excess = [&](const Eigen::VectorXd& a) { return (a - free).dot(ldlt.solve(a - free)); };
    auto candidate = [&](unsigned mask) {
      Eigen::VectorXd a = low;
      for (int p = 0; p < k; ++p)
        if (mask >> p & 1u) a[p] += seams.sign[p] < 0 ? 2.0 : 1.0;
      return a;
    };
    double best = excess(rounded);
    if (k <= kMaxJointSeams) {
      for (unsigned mask = 0; mask < (1u << k); ++mask) {
        const Eigen::VectorXd a = candidate(mask);
        const double e = excess(a);
        if (e < best - 1e-12 * std::abs(best)) best = e, rounded = a;
      }
    } else {
      for (bool improved = true; improved;) {
        improved = false;
        for (int p = 0; p < k; ++p) {
          Eigen::VectorXd a = rounded;
          const double step = seams.sign[p] < 0 ? 2.0 : 1.0;
          a[p] = a[p] == low[p] ? low[p] + step : low[p];
          const double e = excess(a);
          if (e < best - 1e-12 * std::abs(best)) best = e, rounded = a, improved = true;
        }
      }
    }
  }
  for (int p = 0; p < k; ++p) (*offsets)[p] = rounded[p];
}

// With seams: PoissonFit with free offsets, the offsets rounded to whole levels together,
// then again with them fixed (QuadCover's rounding, in one step: the seams are few).
Status SeamedPoissonFit(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<Eigen::Vector3d>& target,
                        const std::vector<double>& omega, double h, int family, LevelSetSeams* seams,
                        std::vector<double>* u) {
  Eigen::MatrixXd block;
  PQ_RETURN_IF_ERROR(PoissonFit(s, geo, target, omega, u, seams, family, true, h, &block));
  RoundOffsets(*seams, family == 0 ? &seams->phi_offset : &seams->psi_offset, &block);
  return PoissonFit(s, geo, target, omega, u, seams, family, false, h);
}

// The seams' signs: the oriented field n × d of OrientedCrossField, compared across each seam
// edge (the cut surface is a disc with every uncancelled singularity on its boundary, so the
// orientation is consistent within it); the majority of a path's edges decides.
std::vector<int> SeamSigns(const SeamCut& cut, const std::vector<Eigen::Vector3d>& oriented) {
  std::vector<double> vote(cut.num_paths(), 0.0);
  for (const auto& e : cut.seam_edges()) vote[e.path] += oriented[e.minus_face].dot(oriented[e.plus_face]);
  std::vector<int> sign(cut.num_paths());
  for (int p = 0; p < cut.num_paths(); ++p) sign[p] = vote[p] >= 0.0 ? 1 : -1;
  return sign;
}

// Makes the transitions exact: every plus copy (and every tip of a sign −1 seam) takes the
// value its minus copy implies.
void ProjectTransitions(const LevelSetSeams& seams, const std::vector<double>& offsets, std::vector<double>* u) {
  for (const auto& pair : seams.cut->copy_pairs()) {
    const double sign = seams.sign[pair.path], a = offsets[pair.path];
    if (pair.minus != pair.plus) (*u)[pair.plus] = sign * (*u)[pair.minus] + a;
    else if (sign < 0) (*u)[pair.minus] = a / 2.0;
  }
}

// Quadratic forms (#V by #V) of the φ energies without the spacing term: alignment
// Σ w_f A_f h² ⟨∇φ, d⟩² and smoothness Σ_e A_e h⁴ |∇φ_f − ∇φ_g|² / ℓ_e², and the Dirichlet
// energy Σ_f A_f h² |∇φ|².
void AddFaceForm(const Eigen::Vector3d& a, const std::array<int, 3>& ids, double scale,
                 std::vector<Eigen::Triplet<double>>* t) {
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) t->emplace_back(ids[p], ids[q], scale * a[p] * a[q]);
}

Eigen::SparseMatrix<double> AlignmentSmoothnessForm(const SurfaceModel& s, const LevelSetGeometry& geo,
                                                    const GuidanceField& g, const std::vector<InteriorEdge>& edges,
                                                    double h, const LevelsetWeights& w) {
  std::vector<Eigen::Triplet<double>> t;
  for (int f = 0; f < s.num_faces(); ++f)
    AddFaceForm(geo.G[f].transpose() * g.direction[f], s.face_vertices(f),
                w.alignment * g.weight[f] * s.face_area(f) * h * h, &t);
  for (const auto& e : edges) {
    const std::array<int, 4> ids{e.i, e.j, e.k, e.l};
    Eigen::Matrix<double, 3, 4> D;
    D << e.Gf.col(0) - e.Gg.col(0), e.Gf.col(1) - e.Gg.col(1), e.Gf.col(2), -e.Gg.col(2);
    const Eigen::Matrix4d block = D.transpose() * D * (w.smoothness * e.area * std::pow(h, 4) / (e.distance * e.distance));
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q) t.emplace_back(ids[p], ids[q], block(p, q));
  }
  Eigen::SparseMatrix<double> N(s.num_vertices(), s.num_vertices());
  N.setFromTriplets(t.begin(), t.end());
  return N;
}

// The best compromise between alignment and smoothness that a single-valued φ can make:
// the smallest generalised eigenvector of (alignment + smoothness, Dirichlet energy), found
// by inverse iteration from `phi` (Knöppel et al.'s globally optimal direction fields use the
// same idea). No orientation of the guidance line field is needed. Scaled to mean h|∇φ| = 1.
Status SmallestEigenvector(const SurfaceModel& s, const LevelSetGeometry& geo, const GuidanceField& g,
                           const std::vector<InteriorEdge>& edges, double h, const LevelsetWeights& w,
                           std::vector<double>* phi) {
  const Eigen::SparseMatrix<double> N = AlignmentSmoothnessForm(s, geo, g, edges, h, w);
  const Eigen::SparseMatrix<double> K = CotanStiffness(s) * (h * h);
  Eigen::VectorXd mass(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v) mass[v] = s.vertex_area(v);
  // B = N + τ K + ε M is positive definite; it has the eigenvectors of the pencil (N, K).
  const double tau = 1e-3 * N.diagonal().sum() / K.diagonal().sum();
  const double epsilon = 1e-9 * K.diagonal().sum() / mass.sum();
  Eigen::SparseMatrix<double> B = N + tau * K;
  for (int v = 0; v < s.num_vertices(); ++v) B.coeffRef(v, v) += epsilon * mass[v];
  CholmodSolver solver;
  PQ_RETURN_IF_ERROR(solver.Factorize(B).WithContext("levelset initial guess"));
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(phi->data(), s.num_vertices());
  for (int iteration = 0; iteration < 60; ++iteration) {
    Eigen::VectorXd next;
    PQ_RETURN_IF_ERROR(solver.Solve(Eigen::VectorXd(K * x), &next));
    next.array() -= next.dot(mass) / mass.sum();  // constants are not a layout
    const double norm = std::sqrt(next.dot(K * next));
    if (!(norm > 0.0)) break;
    x = next / norm;
  }
  double gradient_sum = 0.0;
  std::vector<double> values(x.data(), x.data() + x.size());
  for (int f = 0; f < s.num_faces(); ++f) gradient_sum += s.face_area(f) * Gradient(geo, s, f, values).norm();
  const double scale = s.total_area() / (h * gradient_sum);
  for (int v = 0; v < s.num_vertices(); ++v) (*phi)[v] = scale * x[v];
  return Status::Ok();
}

// The gradient ψ should have: across the direction conjugate to φ's level lines
// (c = n × S̃ t̂1, falling back to orthogonal where c is too close to t̂1), length 1/h,
// oriented so that n · (∇φ × ∇ψ) > 0.
std::vector<Eigen::Vector3d> ConjugateTargets(const SurfaceModel& s, const LevelSetGeometry& geo,
                                              const std::vector<double>& phi, double h, double min_angle) {
  std::vector<Eigen::Vector3d> target(s.num_faces());
  for (int f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d& n = s.face_normal(f);
    const Eigen::Vector3d gphi = Gradient(geo, s, f, phi);
    const Eigen::Vector3d t1 = n.cross(gphi).normalized();
    const Eigen::Matrix3d S = ConjugacyResidual::Regularised(geo.S[f], n, geo.flat_curvature);
    Eigen::Vector3d c = n.cross(S * t1).normalized();
    if (!c.allFinite() || c.cross(t1).norm() < std::sin(min_angle)) c = n.cross(t1);
    Eigen::Vector3d across = n.cross(c) / h;
    if (n.dot(gphi.cross(across)) < 0.0) across = -across;
    target[f] = across;
  }
  return target;
}


// The initial guess (seams: null, or with the seams' transitions; their offsets are set here):
// φ from the oriented cross field (weak pull where the guidance is weak),
// then ψ from the conjugate direction of φ's level lines.
Status InitialGuess(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<InteriorEdge>& edges,
                    const GuidanceField& g, const LevelsetOptions& options, double h, LevelSetSeams* seams,
                    LevelSetSolution* solution) {
  const double min_angle = options.min_angle / kDegrees;
  std::vector<Eigen::Vector3d> target = OrientedCrossField(s, g);
  for (auto& t : target) t /= h;
  std::vector<double> omega(s.num_faces());
  for (int f = 0; f < s.num_faces(); ++f) omega[f] = std::max(g.weight[f], 0.05);
  if (seams != nullptr) {
    // On the cut surface the oriented field (`target`, from which SolveWithSeams took the
    // signs) has no hidden branch cut left: the Poisson fit with the seams' transitions is
    // the guess (the eigenvector below is for a single-valued φ).
    seams->phi_offset.assign(seams->cut->num_paths(), 0.0);
    seams->psi_offset.assign(seams->cut->num_paths(), 0.0);
    PQ_RETURN_IF_ERROR(SeamedPoissonFit(s, geo, target, omega, h, 0, seams, &solution->phi));
    return SeamedPoissonFit(s, geo, ConjugateTargets(s, geo, solution->phi, h, min_angle),
                            std::vector<double>(s.num_faces(), 1.0), h, 1, seams, &solution->psi);
  }
  PQ_RETURN_IF_ERROR(PoissonFit(s, geo, target, omega, &solution->phi));
  PQ_RETURN_IF_ERROR(SmallestEigenvector(s, geo, g, edges, h, options.weights, &solution->phi));
  return PoissonFit(s, geo, ConjugateTargets(s, geo, solution->phi, h, min_angle),
                    std::vector<double>(s.num_faces(), 1.0), &solution->psi);
}

}  // namespace levelset_internal
}  // namespace pqlayout
