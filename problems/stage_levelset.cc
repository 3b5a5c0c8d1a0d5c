// Stage `levelset`: see problems/levelset.h.
#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <sstream>

#include "geometry/closest_point.h"
#include "geometry/differential_operators.h"
#include "geometry/field_writers.h"
#include "geometry/line_field_singularities.h"
#include "geometry/principal_directions.h"
#include "geometry/remesh.h"
#include "problems/figures.h"
#include "problems/levelset.h"
#include "problems/panel_area.h"
#include "problems/residuals/alignment_residual.h"
#include "problems/residuals/conjugacy_residual.h"
#include "problems/residuals/smoothness_residual.h"
#include "problems/residuals/spacing_residual.h"
#include "problems/residuals/transversality_residual.h"
#include "problems/stages.h"
#include "problems/surface_fields.h"
#include "solver/affine_mapped_cost.h"
#include "solver/ceres_options.h"
#include "solver/cholmod_solver.h"

namespace pqlayout {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

// Per-face data shared by every term, computed once.
struct LevelSetGeometry {
  std::vector<Eigen::Matrix3d> G;      // P1 basis gradients, columns in face_vertices order
  std::vector<Eigen::Matrix3d> S;      // shape operators
  std::vector<Eigen::Vector3d> centroid;
  double flat_curvature = 0.0;         // μ: below this curvature, conjugacy becomes orthogonality
};

LevelSetGeometry Precompute(const SurfaceModel& surface) {
  LevelSetGeometry geo;
  geo.S = FaceShapeOperators(surface);
  geo.G.resize(surface.num_faces());
  geo.centroid.resize(surface.num_faces());
  double curvature_integral = 0.0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto g = FaceBasisGradients(surface, f);
    geo.G[f] << g[0], g[1], g[2];
    const auto ids = surface.face_vertices(f);
    geo.centroid[f] = (surface.position(ids[0]) + surface.position(ids[1]) + surface.position(ids[2])) / 3.0;
    curvature_integral += surface.face_area(f) * ConjugacyResidual::CurvatureSum(geo.S[f], surface.face_normal(f));
  }
  // μ = 10 % of the mean |κ1| + |κ2|: flat parts of a curved roof fall back to orthogonal
  // grid lines, the curved parts are conjugate.
  geo.flat_curvature = std::max(1e-12, 0.1 * curvature_integral / surface.total_area());
  return geo;
}

Eigen::Vector3d Gradient(const LevelSetGeometry& geo, const SurfaceModel& s, int f, const std::vector<double>& u) {
  const auto ids = s.face_vertices(f);
  return geo.G[f] * Eigen::Vector3d(u[ids[0]], u[ids[1]], u[ids[2]]);
}

// An interior edge (i, j) between face f (third vertex k) and face g (third vertex l).
struct InteriorEdge {
  int i, j, k, l;
  Eigen::Matrix3d Gf, Gg;  // basis gradients in the order (i, j, k) and (i, j, l)
  double area, distance;
};

Eigen::Matrix3d OrderedBasis(const LevelSetGeometry& geo, const SurfaceModel& s, int f, const std::array<int, 3>& order) {
  const auto ids = s.face_vertices(f);
  Eigen::Matrix3d ordered;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      if (ids[k] == order[c]) ordered.col(c) = geo.G[f].col(k);
  return ordered;
}

std::vector<InteriorEdge> InteriorEdges(const SurfaceModel& s, const LevelSetGeometry& geo) {
  const TriMesh& mesh = s.mesh();
  std::vector<InteriorEdge> edges;
  for (const auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    const auto h = mesh.halfedge_handle(e, 0), o = mesh.opposite_halfedge_handle(h);
    const int f = mesh.face_handle(h).idx(), g = mesh.face_handle(o).idx();
    InteriorEdge edge;
    edge.i = mesh.from_vertex_handle(h).idx();
    edge.j = mesh.to_vertex_handle(h).idx();
    edge.k = mesh.to_vertex_handle(mesh.next_halfedge_handle(h)).idx();
    edge.l = mesh.to_vertex_handle(mesh.next_halfedge_handle(o)).idx();
    edge.Gf = OrderedBasis(geo, s, f, {edge.i, edge.j, edge.k});
    edge.Gg = OrderedBasis(geo, s, g, {edge.i, edge.j, edge.l});
    edge.area = (s.face_area(f) + s.face_area(g)) / 3.0;
    edge.distance = (geo.centroid[f] - geo.centroid[g]).norm();
    edges.push_back(edge);
  }
  return edges;
}

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
// seams' offsets (not rounded).
Status PoissonFit(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<Eigen::Vector3d>& target,
                  const std::vector<double>& omega, std::vector<double>* u, LevelSetSeams* seams = nullptr,
                  int family = 0, bool free_offsets = false, double h = 1.0) {
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
  if (has_seams && free_offsets)
    for (int p = 0; p < seams->cut->num_paths(); ++p) (*offsets)[p] = x[first_offset + p];
  return Status::Ok();
}

// Offsets to whole levels; odd ones across sign −1 seams, so that the branch point (u = a/2
// there) lies half a level from every φ and ψ line, in the middle of a cell: that cell is a
// hexagon (the cone angle there is 3π), which extraction cuts into two quads, leaving two
// vertices where five quads meet. With even offsets the lines would run through the branch
// point, where P1 level lines of a cone point crowd and cross at small angles.
void RoundOffsets(const LevelSetSeams& seams, std::vector<double>* offsets) {
  for (size_t p = 0; p < offsets->size(); ++p) {
    double& a = (*offsets)[p];
    a = seams.sign[p] < 0 ? 2.0 * std::round((a - 1.0) / 2.0) + 1.0 : std::round(a);
  }
}

// With seams: PoissonFit with free offsets, the offsets rounded to whole levels, then again
// with them fixed (QuadCover's rounding, in one step: the seams are few and far apart).
Status SeamedPoissonFit(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<Eigen::Vector3d>& target,
                        const std::vector<double>& omega, double h, int family, LevelSetSeams* seams,
                        std::vector<double>* u) {
  PQ_RETURN_IF_ERROR(PoissonFit(s, geo, target, omega, u, seams, family, true, h));
  RoundOffsets(*seams, family == 0 ? &seams->phi_offset : &seams->psi_offset);
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

// ---- Ceres ---------------------------------------------------------------------------

class ProgressLog : public ceres::IterationCallback {
 public:
  explicit ProgressLog(std::string name) : name_(std::move(name)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    VLOG(1) << name_ << " iteration " << it.iteration << ": cost " << it.cost;
    if (it.iteration > 0 && it.iteration % 25 == 0)
      LOG(INFO) << "levelset: " << name_ << " iteration " << it.iteration << ", cost " << it.cost;
    return ceres::SOLVER_CONTINUE;
  }

 private:
  std::string name_;
};

nlohmann::json SummaryJson(const ceres::Solver::Summary& s) {
  return {{"iterations", s.iterations.size() > 0 ? s.iterations.size() - 1 : 0},
          {"initial_cost", s.initial_cost},
          {"final_cost", s.final_cost},
          {"termination", ceres::TerminationTypeToString(s.termination_type)},
          {"seconds", s.total_time_in_seconds},
          {"residual_blocks", s.num_residual_blocks},
          {"message", s.message}};
}

Status Solve(const std::string& name, int max_iterations, ceres::Problem* problem, nlohmann::json* summary) {
  ceres::Solver::Options options = SparseCholeskyOptions(max_iterations);
  ProgressLog progress(name);
  options.callbacks.push_back(&progress);
  ceres::Solver::Summary result;
  ceres::Solve(options, problem, &result);
  *summary = SummaryJson(result);
  VLOG(1) << "levelset: " << name << ":\n" << result.FullReport();
  if (!result.IsSolutionUsable()) return Status::Internal("levelset: Ceres failed on " + name + ": " + result.message);
  LOG(INFO) << "levelset: " << name << ": " << result.iterations.size() - 1 << " iterations, cost "
            << result.initial_cost << " → " << result.final_cost << " ("
            << ceres::TerminationTypeToString(result.termination_type) << ", " << result.total_time_in_seconds << " s)";
  return Status::Ok();
}

ceres::LossFunction* Weight(double w) { return new ceres::ScaledLoss(nullptr, w, ceres::TAKE_OWNERSHIP); }

// `live`: vertex mask; a term is added if it touches a live vertex (nullptr: all).
bool Live(const std::vector<char>* live, std::initializer_list<int> ids) {
  if (live == nullptr) return true;
  for (const int v : ids)
    if ((*live)[v]) return true;
  return false;
}

// Where the value of each vertex of the solve mesh lives for Ceres: its own parameter, or,
// for the plus copy of a seam vertex, the minus copy's parameter through u₊ = s·u₋ + a
// (solver/affine_mapped_cost.h), so the transitions hold exactly.
struct Scalar {
  int vertex;
  double scale = 1.0, offset = 0.0;
};
struct Chart {
  std::vector<double>* values;
  std::vector<Scalar> map;  // per vertex; empty: every vertex is its own parameter
  Scalar At(int v) const { return map.empty() ? Scalar{v} : map[v]; }
};

// Adds `cost` over the given scalars (chart, vertex), through their maps.
void AddMapped(ceres::Problem* problem, ceres::CostFunction* cost, ceres::LossFunction* loss,
               std::initializer_list<std::pair<const Chart*, Scalar>> args) {
  std::vector<double*> blocks;
  std::vector<double> scale, offset;
  bool identity = true;
  for (const auto& [chart, x] : args) {
    blocks.push_back(&(*chart->values)[x.vertex]);
    scale.push_back(x.scale);
    offset.push_back(x.offset);
    identity = identity && x.scale == 1.0 && x.offset == 0.0;
  }
  if (!identity) cost = new AffineMappedCost(cost, std::move(scale), std::move(offset));
  problem->AddResidualBlock(cost, loss, blocks);
}

void AddSmoothness(const std::vector<InteriorEdge>& edges, double h, double weight, const Chart& u,
                   ceres::Problem* problem, const std::vector<char>* live = nullptr) {
  if (weight <= 0.0) return;
  for (const auto& e : edges) {
    if (!Live(live, {e.i, e.j, e.k, e.l})) continue;
    AddMapped(problem, SmoothnessResidual::Create(e.Gf, e.Gg, e.area, e.distance, h), Weight(weight),
              {{&u, u.At(e.i)}, {&u, u.At(e.j)}, {&u, u.At(e.k)}, {&u, u.At(e.l)}});
  }
}

void AddSpacing(const SurfaceModel& s, const LevelSetGeometry& geo, double h, double weight, const Chart& u,
                ceres::Problem* problem, const std::vector<char>* live = nullptr) {
  if (weight <= 0.0) return;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    if (!Live(live, {ids[0], ids[1], ids[2]})) continue;
    AddMapped(problem, SpacingResidual::Create(geo.G[f], s.face_area(f), h), Weight(weight),
              {{&u, u.At(ids[0])}, {&u, u.At(ids[1])}, {&u, u.At(ids[2])}});
  }
}

}  // namespace

nlohmann::json LevelSetMetrics::ToJson() const {
  return {{"alignment_rms_deg", alignment_rms_deg},
          {"alignment_rms_deg_weight_above_half", alignment_rms_deg_strong},
          {"spacing_cv_phi", spacing_cv_phi},
          {"spacing_cv_psi", spacing_cv_psi},
          {"spacing_cv_phi_weight_above_half", spacing_cv_phi_strong},
          {"spacing_cv_psi_weight_above_half", spacing_cv_psi_strong},
          {"conjugacy_rms", conjugacy_rms},
          {"min_crossing_angle_deg", min_crossing_angle_deg},
          {"faces_below_min_angle", faces_below_min_angle},
          {"area_fraction_below_min_angle", area_below_min_angle},
          {"foldovers", foldovers}};
}

namespace {

// Area-weighted coefficient of variation of the local spacing 1/|∇u| over faces with mask.
double SpacingCv(const SurfaceModel& s, const std::vector<Eigen::Vector3d>& gradient, const std::vector<char>& mask) {
  double area = 0.0, sum = 0.0, sum_sq = 0.0;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (!mask[f] || gradient[f].norm() <= 0.0) continue;
    const double spacing = 1.0 / gradient[f].norm(), a = s.face_area(f);
    area += a;
    sum += a * spacing;
    sum_sq += a * spacing * spacing;
  }
  if (area <= 0.0) return 0.0;
  const double mean = sum / area;
  return std::sqrt(std::max(0.0, sum_sq / area - mean * mean)) / mean;
}

LevelSetMetrics Measure(const SurfaceModel& s, const LevelSetGeometry& geo, const GuidanceField& g,
                        const std::vector<double>& phi, const std::vector<double>& psi, double min_angle_deg) {
  LevelSetMetrics m;
  std::vector<Eigen::Vector3d> gphi(s.num_faces()), gpsi(s.num_faces());
  std::vector<char> all(s.num_faces(), 1), strong(s.num_faces(), 0);
  double align = 0.0, align_w = 0.0, align_s = 0.0, align_sw = 0.0, conj = 0.0;
  m.min_crossing_angle_deg = 90.0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d& n = s.face_normal(f);
    gphi[f] = Gradient(geo, s, f, phi);
    gpsi[f] = Gradient(geo, s, f, psi);
    strong[f] = g.weight[f] > 0.5;
    const double sine = std::min(1.0, std::abs(gphi[f].normalized().dot(g.direction[f])));
    const double angle = std::asin(sine) * kDegrees, wa = g.weight[f] * s.face_area(f);
    align += wa * angle * angle;
    align_w += wa;
    if (strong[f]) align_s += wa * angle * angle, align_sw += wa;
    const Eigen::Vector3d t1 = n.cross(gphi[f]).normalized(), t2 = n.cross(gpsi[f]).normalized();
    const Eigen::Matrix3d S = ConjugacyResidual::Regularised(geo.S[f], n, geo.flat_curvature);
    const double c = t1.dot(S * t2) / (ConjugacyResidual::CurvatureSum(geo.S[f], n) + geo.flat_curvature);
    if (std::isfinite(c)) conj += s.face_area(f) * c * c;
    const double crossing = std::acos(std::min(1.0, std::abs(t1.dot(t2)))) * kDegrees;
    if (std::isfinite(crossing)) m.min_crossing_angle_deg = std::min(m.min_crossing_angle_deg, crossing);
    if (!(crossing >= min_angle_deg)) {
      ++m.faces_below_min_angle, m.area_below_min_angle += s.face_area(f);
      VLOG(2) << "levelset: face " << f << " at " << geo.centroid[f].transpose() << " crosses at " << crossing << "°";
    }
    if (!(n.dot(gphi[f].cross(gpsi[f])) > 0.0)) ++m.foldovers;
  }
  m.alignment_rms_deg = align_w > 0 ? std::sqrt(align / align_w) : 0.0;
  m.alignment_rms_deg_strong = align_sw > 0 ? std::sqrt(align_s / align_sw) : 0.0;
  m.spacing_cv_phi = SpacingCv(s, gphi, all);
  m.spacing_cv_psi = SpacingCv(s, gpsi, all);
  m.spacing_cv_phi_strong = SpacingCv(s, gphi, strong);
  m.spacing_cv_psi_strong = SpacingCv(s, gpsi, strong);
  m.conjugacy_rms = std::sqrt(conj / s.total_area());
  m.area_below_min_angle /= s.total_area();
  return m;
}

}  // namespace

LevelSetMetrics MeasureLevelSets(const SurfaceModel& surface, const GuidanceField& guidance,
                                 const std::vector<double>& phi, const std::vector<double>& psi,
                                 double min_angle_deg) {
  return Measure(surface, Precompute(surface), guidance, phi, psi, min_angle_deg);
}

namespace {

// ---- Crossing-angle rounds ------------------------------------------------------------
//
// The transversality hinge is a penalty: at the joint optimum it balances against
// alignment and spacing, and leaves a few percent of the faces crossing below min_angle
// (on the Great Court near the guidance singularities and the rectangle's corners; with a
// global weight ×10 the solve stalls and folds instead). So after the joint solve the
// faces still crossing below min_angle + kCrossingSlack get their transversality weight
// multiplied by kCrossingBoost, the hinge is raised by kCrossingMargin, and φ, ψ are
// re-solved near those faces only: ψ within kPsiRings vertex rings, φ within kPhiRings
// (φ moves as little as possible, to keep its alignment); the rest is held. Repeated until
// no face crosses below min_angle or levelset.crossing_rounds is used up.
constexpr double kCrossingSlack = 1.0;   // degrees above min_angle that still count as failing
constexpr double kCrossingMargin = 1.5;  // degrees the hinge is raised by in the rounds
constexpr double kCrossingBoost = 4.0;   // weight factor per round on a failing face
constexpr int kPhiRings = 1, kPsiRings = 3;
constexpr int kCrossingIterations = 30;  // Ceres iterations per round

// Marks the failing faces (see above), multiplies their boost and returns how many faces
// cross below min_angle (0: nothing to do). live_phi / live_psi: the vertices free to move.
int RaiseCrossings(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<double>& phi,
                   const std::vector<double>& psi, double min_angle, std::vector<double>* boost,
                   std::vector<char>* live_phi, std::vector<char>* live_psi) {
  int below = 0;
  const double sin_failing = std::sin(min_angle + kCrossingSlack / kDegrees);
  std::vector<char> live(s.num_vertices(), 0);
  for (int f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d a = Gradient(geo, s, f, phi), b = Gradient(geo, s, f, psi);
    const double sine = s.face_normal(f).dot(a.cross(b)) / (a.norm() * b.norm());
    if (!(sine >= std::sin(min_angle))) ++below;
    if (sine >= sin_failing) continue;
    (*boost)[f] *= kCrossingBoost;
    for (const int v : s.face_vertices(f)) live[v] = 1;
  }
  for (int ring = 1; ring <= std::max(kPhiRings, kPsiRings); ++ring) {
    std::vector<char> next = live;
    for (int v = 0; v < s.num_vertices(); ++v)
      if (live[v])
        for (const auto u : s.mesh().vv_range(VertexHandle(v))) next[u.idx()] = 1;
    live.swap(next);
    if (ring == kPhiRings) *live_phi = live;
    if (ring == kPsiRings) *live_psi = live;
  }
  return below;
}

// A seam edge as the seam smoothness term sees it (cut vertex ids): i, j, k in the minus face
// f, i, j, l in the plus face g (i, j the same original vertices).
struct SeamEdgeTerm {
  int path;
  int i_minus, j_minus, k, i_plus, j_plus, l;
  Eigen::Matrix3d Gf, Gg;
  double area, distance;
};

std::vector<SeamEdgeTerm> SeamEdgeTerms(const SurfaceModel& s, const LevelSetGeometry& geo, const SeamCut& cut) {
  std::vector<SeamEdgeTerm> terms;
  for (const auto& e : cut.seam_edges()) {
    const auto ids_f = s.face_vertices(e.minus_face), ids_g = s.face_vertices(e.plus_face);
    const TriMesh& m = s.mesh();
    const auto h = m.halfedge_handle(EdgeHandle(e.cut_edge_minus), 0);
    const int a = cut.original_vertex(m.from_vertex_handle(h).idx()), b = cut.original_vertex(m.to_vertex_handle(h).idx());
    SeamEdgeTerm t;
    t.path = e.path;
    t.i_minus = t.j_minus = t.k = t.i_plus = t.j_plus = t.l = -1;
    for (int c = 0; c < 3; ++c) {
      const int of = cut.original_vertex(ids_f[c]), og = cut.original_vertex(ids_g[c]);
      (of == a ? t.i_minus : of == b ? t.j_minus : t.k) = ids_f[c];
      (og == a ? t.i_plus : og == b ? t.j_plus : t.l) = ids_g[c];
    }
    t.Gf = OrderedBasis(geo, s, e.minus_face, {t.i_minus, t.j_minus, t.k});
    t.Gg = OrderedBasis(geo, s, e.plus_face, {t.i_plus, t.j_plus, t.l});
    t.area = (s.face_area(e.minus_face) + s.face_area(e.plus_face)) / 3.0;
    t.distance = (geo.centroid[e.minus_face] - geo.centroid[e.plus_face]).norm();
    terms.push_back(t);
  }
  return terms;
}

// The level sets on the mesh they are solved on (see SolveLevelSets for the working mesh).
// seams: null, or the seams s is the cut surface of, with their signs (SolveWithSeams); the
// offsets are set here.
Status SolveOnMesh(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                   LevelSetSeams* seams, LevelSetSolution* solution) {
  const LevelSetGeometry geo = Precompute(s);
  const std::vector<InteriorEdge> edges = InteriorEdges(s, geo);
  const auto& w = options.weights;
  const double min_angle = options.min_angle / kDegrees;
  const bool seamed = seams != nullptr && seams->cut != nullptr;

  // Initial guess: φ from the oriented cross field (weak pull where the guidance is weak),
  // then ψ from the conjugate direction of φ's level lines.
  std::vector<Eigen::Vector3d> target = OrientedCrossField(s, g);
  for (auto& t : target) t /= h;
  std::vector<double> omega(s.num_faces());
  for (int f = 0; f < s.num_faces(); ++f) omega[f] = std::max(g.weight[f], 0.05);
  std::vector<SeamEdgeTerm> seam_terms;
  if (seamed) {
    // On the cut surface the oriented field (`target`, from which SolveWithSeams took the
    // signs) has no hidden branch cut left: the Poisson fit with the seams' transitions is
    // the guess (the eigenvector below is for a single-valued φ).
    seams->phi_offset.assign(seams->cut->num_paths(), 0.0);
    seams->psi_offset.assign(seams->cut->num_paths(), 0.0);
    seam_terms = SeamEdgeTerms(s, geo, *seams->cut);
    PQ_RETURN_IF_ERROR(SeamedPoissonFit(s, geo, target, omega, h, 0, seams, &solution->phi));
    PQ_RETURN_IF_ERROR(SeamedPoissonFit(s, geo, ConjugateTargets(s, geo, solution->phi, h, min_angle),
                                        std::vector<double>(s.num_faces(), 1.0), h, 1, seams, &solution->psi));
  } else {
    PQ_RETURN_IF_ERROR(PoissonFit(s, geo, target, omega, &solution->phi));
    PQ_RETURN_IF_ERROR(SmallestEigenvector(s, geo, g, edges, h, w, &solution->phi));
    PQ_RETURN_IF_ERROR(PoissonFit(s, geo, ConjugateTargets(s, geo, solution->phi, h, min_angle),
                                  std::vector<double>(s.num_faces(), 1.0), &solution->psi));
  }

  std::vector<double>& phi = solution->phi;
  std::vector<double>& psi = solution->psi;
  Chart phi_chart{&phi, {}}, psi_chart{&psi, {}};
  std::vector<int> fixed_tips;  // branch points of sign −1 seams: u = a/2 on both sides
  if (seamed) {
    phi_chart.map = psi_chart.map = std::vector<Scalar>(s.num_vertices());
    for (int v = 0; v < s.num_vertices(); ++v) phi_chart.map[v] = psi_chart.map[v] = {v};
    for (const auto& pair : seams->cut->copy_pairs()) {
      const double sign = seams->sign[pair.path];
      if (pair.minus == pair.plus) {
        if (sign < 0) fixed_tips.push_back(pair.minus);
        continue;
      }
      phi_chart.map[pair.plus] = {pair.minus, sign, seams->phi_offset[pair.path]};
      psi_chart.map[pair.plus] = {pair.minus, sign, seams->psi_offset[pair.path]};
    }
  }
  const auto project = [&] {
    if (!seamed) return;
    ProjectTransitions(*seams, seams->phi_offset, &phi);
    ProjectTransitions(*seams, seams->psi_offset, &psi);
  };
  const auto hold_tips = [&](ceres::Problem* problem) {
    for (const int v : fixed_tips)
      for (double* x : {&phi[v], &psi[v]})
        if (problem->HasParameterBlock(x)) problem->SetParameterBlockConstant(x);
  };
  // Smoothness across the seams: f on the minus side, g on the plus side; with the plus face's
  // third vertex l read as s·(u_l − a) (its plus-chart value mapped back), the ordinary
  // smoothness term measures ∇u_f − s·∇u_g, the jump in one chart.
  const auto add_seam_smoothness = [&](ceres::Problem* problem, const Chart& u, const std::vector<double>& offsets,
                                       const std::vector<char>* live) {
    if (w.smoothness <= 0.0) return;
    for (const auto& t : seam_terms) {
      if (!Live(live, {t.i_minus, t.j_minus, t.k, t.l})) continue;
      const double sign = seams->sign[t.path];
      Scalar l = u.At(t.l);
      l = {l.vertex, sign * l.scale, sign * (l.offset - offsets[t.path])};
      AddMapped(problem, SmoothnessResidual::Create(t.Gf, t.Gg, t.area, t.distance, h), Weight(w.smoothness),
                {{&u, u.At(t.i_minus)}, {&u, u.At(t.j_minus)}, {&u, u.At(t.k)}, {&u, l}});
    }
  };
  // φ's terms: alignment + spacing + smoothness.
  auto add_phi_terms = [&](ceres::Problem* problem, const std::vector<char>* live = nullptr) {
    for (int f = 0; f < s.num_faces(); ++f) {
      const auto ids = s.face_vertices(f);
      if (!Live(live, {ids[0], ids[1], ids[2]})) continue;
      if (w.alignment > 0.0 && g.weight[f] > 0.0)
        AddMapped(problem, AlignmentResidual::Create(geo.G[f], g.direction[f], g.weight[f], s.face_area(f), h),
                  Weight(w.alignment),
                  {{&phi_chart, phi_chart.At(ids[0])}, {&phi_chart, phi_chart.At(ids[1])},
                   {&phi_chart, phi_chart.At(ids[2])}});
    }
    AddSpacing(s, geo, h, w.spacing, phi_chart, problem, live);
    AddSmoothness(edges, h, w.smoothness, phi_chart, problem, live);
    if (seamed) add_seam_smoothness(problem, phi_chart, seams->phi_offset, live);
  };
  std::vector<double> boost(s.num_faces(), 1.0);  // per-face transversality weight factor (RaiseCrossings)
  // ψ's terms: conjugacy + transversality (both also involve φ) + spacing + smoothness.
  double hinge_angle = min_angle;
  auto add_psi_terms = [&](ceres::Problem* problem, const std::vector<char>* live = nullptr) {
    for (int f = 0; f < s.num_faces(); ++f) {
      const auto ids = s.face_vertices(f);
      if (!Live(live, {ids[0], ids[1], ids[2]})) continue;
      const std::initializer_list<std::pair<const Chart*, Scalar>> blocks{
          {&phi_chart, phi_chart.At(ids[0])}, {&phi_chart, phi_chart.At(ids[1])}, {&phi_chart, phi_chart.At(ids[2])},
          {&psi_chart, psi_chart.At(ids[0])}, {&psi_chart, psi_chart.At(ids[1])}, {&psi_chart, psi_chart.At(ids[2])}};
      const Eigen::Vector3d& n = s.face_normal(f);
      if (w.conjugacy > 0.0)
        AddMapped(problem, ConjugacyResidual::Create(geo.G[f], n, geo.S[f], geo.flat_curvature, s.face_area(f)),
                  Weight(w.conjugacy), blocks);
      if (w.transversality > 0.0)
        AddMapped(problem, TransversalityResidual::Create(geo.G[f], n, hinge_angle, s.face_area(f), h),
                  Weight(w.transversality * boost[f]), blocks);
    }
    AddSpacing(s, geo, h, w.spacing, psi_chart, problem, live);
    AddSmoothness(edges, h, w.smoothness, psi_chart, problem, live);
    if (seamed) add_seam_smoothness(problem, psi_chart, seams->psi_offset, live);
  };

  project();
  solution->initial = Measure(s, geo, g, phi, psi, options.min_angle);
  // 1. φ alone.
  ceres::Problem phi_problem;
  add_phi_terms(&phi_problem);
  hold_tips(&phi_problem);
  if (phi_problem.NumResidualBlocks() > 0)
    PQ_RETURN_IF_ERROR(Solve("phi", options.max_iterations, &phi_problem, &solution->solver["phi"]));
  project();
  // 2. ψ with φ held.
  ceres::Problem psi_problem;
  add_psi_terms(&psi_problem);
  for (double& value : phi)
    if (psi_problem.HasParameterBlock(&value)) psi_problem.SetParameterBlockConstant(&value);
  hold_tips(&psi_problem);
  if (psi_problem.NumResidualBlocks() > 0)
    PQ_RETURN_IF_ERROR(Solve("psi", options.max_iterations, &psi_problem, &solution->solver["psi"]));
  project();
  // 3. Both together, so that φ can give way where ψ cannot cross it steeply enough.
  if (options.joint_iterations > 0) {
    ceres::Problem joint_problem;
    add_phi_terms(&joint_problem);
    add_psi_terms(&joint_problem);
    hold_tips(&joint_problem);
    PQ_RETURN_IF_ERROR(Solve("joint", options.joint_iterations, &joint_problem, &solution->solver["joint"]));
    project();
  }
  // 4. Local re-solves for the crossing angle (see RaiseCrossings).
  for (int round = 0; round < options.crossing_rounds; ++round) {
    std::vector<char> live_phi, live_psi;
    if (RaiseCrossings(s, geo, phi, psi, min_angle, &boost, &live_phi, &live_psi) == 0) break;
    for (int v = 0; v < s.num_vertices(); ++v) {  // a live plus copy frees its parameter
      if (live_phi[v]) live_phi[phi_chart.At(v).vertex] = 1;
      if (live_psi[v]) live_psi[psi_chart.At(v).vertex] = 1;
    }
    hinge_angle = min_angle + kCrossingMargin / kDegrees;
    ceres::Problem local;
    add_phi_terms(&local, &live_psi);
    add_psi_terms(&local, &live_psi);
    for (int v = 0; v < s.num_vertices(); ++v) {
      if (!live_phi[v] && local.HasParameterBlock(&phi[v])) local.SetParameterBlockConstant(&phi[v]);
      if (!live_psi[v] && local.HasParameterBlock(&psi[v])) local.SetParameterBlockConstant(&psi[v]);
    }
    hold_tips(&local);
    const std::string name = "crossing_round_" + std::to_string(round + 1);
    PQ_RETURN_IF_ERROR(Solve(name, kCrossingIterations, &local, &solution->solver[name]));
    project();
  }

  solution->metrics = Measure(s, geo, g, phi, psi, options.min_angle);
  return Status::Ok();
}

// The guidance on the working mesh: each working face takes the direction (projected into
// its plane) and weight of the reference face closest to its centroid.
GuidanceField TransferGuidance(const SurfaceModel& reference, const GuidanceField& g, const SurfaceModel& working) {
  const ClosestPointQuery query(reference);
  GuidanceField out;
  out.scale = g.scale;
  for (int f = 0; f < working.num_faces(); ++f) {
    const auto ids = working.face_vertices(f);
    const Eigen::Vector3d centroid =
        (working.position(ids[0]) + working.position(ids[1]) + working.position(ids[2])) / 3.0;
    const int r = query.OnSurface(centroid).element;
    const Eigen::Vector3d& n = working.face_normal(f);
    Eigen::Vector3d d = g.direction[r] - g.direction[r].dot(n) * n;
    d = d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d(n.unitOrthogonal());
    out.direction.push_back(d);
    out.major.push_back(g.major[r]);
    out.minor.push_back(g.minor[r]);
    out.magnitude.push_back(g.magnitude[r]);
    out.weight.push_back(g.weight[r]);
  }
  return out;
}

constexpr double kWorkingCornerAngle = 30.0;  // corners the working mesh keeps (extract.corner_angle's default)
constexpr double kReuseReference = 0.7;       // solve on the reference if its mean edge ≥ this × working edge
constexpr double kDefaultWorkingEdge = 0.4;   // × h: CGAL lands near 12k triangles on the Great Court at h = 3 m
constexpr int kRemeshIterations = 3;
constexpr double kCancelDistance = 2.0;  // × h: two ±½ singularities closer than this get no seam
constexpr double kMinSeamWeight = 1.0;   // × h: a seam whose path has less weighted length is not cut

// The tips of the seams: the guidance's singularities of index ±½, less the pairs closer
// than kCancelDistance·h, closest first. Around such a pair the field turns by a whole turn
// or none (opposite indices cancel: a wrinkle; equal ones make an index ±1, e.g. a centre
// that the discrete field splits in two), so a single-valued φ can follow it there; two
// seams would only add two branch points.
std::vector<int> SeamTips(const SurfaceModel& s, const GuidanceField& g, double h, int* cancelled) {
  std::vector<LineFieldSingularity> half;
  for (const auto& x : FindLineFieldSingularities(s, g.direction))
    if (std::abs(std::abs(x.index) - 0.5) < 1e-9) half.push_back(x);
  std::vector<std::tuple<double, int, int>> candidates;
  for (size_t i = 0; i < half.size(); ++i)
    for (size_t j = i + 1; j < half.size(); ++j) {
      const double d = (half[i].position - half[j].position).norm();
      if (d < kCancelDistance * h) candidates.emplace_back(d, i, j);
    }
  std::sort(candidates.begin(), candidates.end());
  std::vector<char> gone(half.size(), 0);
  *cancelled = 0;
  for (const auto& [d, i, j] : candidates) {
    if (gone[i] || gone[j]) continue;
    gone[i] = gone[j] = 1;
    ++*cancelled;
  }
  std::vector<int> tips;
  for (size_t i = 0; i < half.size(); ++i)
    if (!gone[i]) tips.push_back(half[i].vertex);
  return tips;
}

// SolveOnMesh on the surface cut open along seams (geometry/seams.h); φ, ψ per original
// vertex are the first copies' values, per cut vertex in phi_cut / psi_cut. A seam is cut
// only where a single-valued φ would have to misalign a weighted length of kMinSeamWeight·h
// or more (PathWeight of its route): on the Great Court the curvature field's four umbilics
// and the ring qualify (3.3–16 m at h = 3 m); the strain field's singularities sit in the
// weak bands along the edges, where a hidden cut costs at most 1.6 m, and get none.
Status SolveWithSeams(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                      LevelSetSolution* solution) {
  LevelSetSeams& seams = solution->seams;
  seams = LevelSetSeams();
  const std::vector<int> tips = SeamTips(s, g, h, &seams.cancelled_pairs);
  std::vector<std::vector<int>> paths;
  for (auto& path : RouteSeams(s, g.weight, tips)) {
    if (PathWeight(s, g.weight, path) >= kMinSeamWeight * h) paths.push_back(std::move(path));
    else ++seams.light_paths;
  }
  std::unique_ptr<SeamCut> cut;
  if (!paths.empty()) {
    // A seam from a singularity must flip the orientation (sign −1). If the guidance on the
    // cut surface says otherwise, the "singularity" was a wrinkle that a nearby uncancelled
    // one undoes (e.g. where two principal directions swap roles): no seam there.
    PQ_RETURN_IF_ERROR(SeamCut::Build(s, paths, &cut).WithContext("levelset seams"));
    seams.sign = SeamSigns(*cut, OrientedCrossField(cut->cut(), g));
    std::vector<std::vector<int>> kept;
    for (size_t p = 0; p < paths.size(); ++p) {
      if (s.is_boundary(paths[p].front()) || seams.sign[p] < 0) kept.push_back(paths[p]);
      else ++seams.orientable_tips;
    }
    if (kept.size() < paths.size()) {
      paths = std::move(kept);
      cut.reset();
      seams.sign.clear();
      if (!paths.empty()) {
        PQ_RETURN_IF_ERROR(SeamCut::Build(s, paths, &cut).WithContext("levelset seams"));
        seams.sign = SeamSigns(*cut, OrientedCrossField(cut->cut(), g));
      }
    }
  }
  if (paths.empty()) return SolveOnMesh(s, g, options, h, nullptr, solution);
  for (const auto& path : paths)
    if (!s.is_boundary(path.front())) seams.tips.push_back(path.front());
  seams.cut = std::move(cut);
  LOG(INFO) << "levelset: " << paths.size() << " seams: " << seams.tips.size() << " from guidance singularities, "
            << paths.size() - seams.tips.size() << " joining holes to the outer boundary (" << seams.cancelled_pairs
            << " close singularity pairs, " << seams.light_paths << " routes through weak guidance and "
            << seams.orientable_tips << " tips the guidance does not flip around left uncut)";
  PQ_RETURN_IF_ERROR(SolveOnMesh(seams.cut->cut(), g, options, h, &seams, solution));
  solution->phi_cut = std::move(solution->phi);
  solution->psi_cut = std::move(solution->psi);
  solution->phi = seams.cut->ToOriginal(solution->phi_cut);
  solution->psi = seams.cut->ToOriginal(solution->psi_cut);
  return Status::Ok();
}

}  // namespace

nlohmann::json LevelSetSeams::ToJson() const {
  nlohmann::json paths = nlohmann::json::array();
  if (cut)
    for (int p = 0; p < cut->num_paths(); ++p)
      paths.push_back({{"vertices", cut->path(p).size()},
                       {"sign", sign[p]},
                       {"phi_offset", static_cast<long>(phi_offset[p])},
                       {"psi_offset", static_cast<long>(psi_offset[p])},
                       {"branch_point", cut->starts_inside(p)}});
  return {{"count", paths.size()},
          {"branch_points", tips.size()},
          {"cancelled_singularity_pairs", cancelled_pairs},
          {"uncut_weak_routes", light_paths},
          {"uncut_orientable_tips", orientable_tips},
          {"on_working_mesh", working != nullptr},
          {"paths", paths}};
}

Status SolveLevelSets(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                      LevelSetSolution* solution) {
  const double working_edge = options.working_edge > 0.0 ? options.working_edge : kDefaultWorkingEdge * h;
  const double reference_edge = MeanEdgeLength(s.mesh());
  if (reference_edge >= kReuseReference * working_edge) {
    solution->working_faces = s.num_faces();
    if (options.seams) return SolveWithSeams(s, g, options, h, solution);
    return SolveOnMesh(s, g, options, h, nullptr, solution);
  }
  // A reference much finer than the layout needs: solve on a remeshed copy whose edges are
  // working_edge long (the level lines are h apart; 0.4 h resolves them), then interpolate
  // φ and ψ to the reference's vertices. Stage time then follows h, not the reference size.
  TriMesh working_mesh;
  PQ_RETURN_IF_ERROR(RemeshIsotropic(s, working_edge, kWorkingCornerAngle, kRemeshIterations, &working_mesh)
                         .WithContext("levelset working mesh"));
  auto working = std::make_shared<const SurfaceModel>(std::move(working_mesh));
  LOG(INFO) << "levelset: reference mean edge " << reference_edge << " m < " << kReuseReference << " × working edge "
            << working_edge << " m: solving on a remeshed copy with " << working->num_faces() << " triangles";
  LevelSetSolution coarse;
  // With seams the solution stays on the working mesh's cut surface (extraction runs there);
  // the per-vertex φ, ψ interpolated below (first copies) are for the field files only.
  const GuidanceField working_guidance = TransferGuidance(s, g, *working);
  if (options.seams) PQ_RETURN_IF_ERROR(SolveWithSeams(*working, working_guidance, options, h, &coarse));
  else PQ_RETURN_IF_ERROR(SolveOnMesh(*working, working_guidance, options, h, nullptr, &coarse));
  const ClosestPointQuery query(*working);
  solution->phi.assign(s.num_vertices(), 0.0);
  solution->psi.assign(s.num_vertices(), 0.0);
  for (int v = 0; v < s.num_vertices(); ++v) {
    const SurfacePoint p = query.OnSurface(s.position(v));
    const Eigen::Vector3d w = TriangleBarycentric(*working, p.element, s.position(v));
    const auto ids = working->face_vertices(p.element);
    for (int k = 0; k < 3; ++k) {
      solution->phi[v] += w[k] * coarse.phi[ids[k]];
      solution->psi[v] += w[k] * coarse.psi[ids[k]];
    }
  }
  // The metrics are those of the solve, on the working mesh: on the reference, a small
  // triangle straddling a kink of the working mesh's piecewise linear φ gets a blend of the
  // two gradients, which says nothing about the layout but would dominate the minimum
  // crossing angle and inflate the spacing CV.
  solution->initial = coarse.initial;
  solution->metrics = coarse.metrics;
  solution->solver = coarse.solver;
  solution->working_faces = working->num_faces();
  if (coarse.seams.cut) {
    solution->seams = std::move(coarse.seams);
    solution->seams.working = working;
    solution->phi_cut = std::move(coarse.phi_cut);
    solution->psi_cut = std::move(coarse.psi_cut);
  }
  return Status::Ok();
}

namespace {

// Scales φ, ψ by `factor` (layout.density: panel_area). With seams the offsets become
// round(factor·a) and φ, ψ are refitted to the scaled gradients under the rounded
// transitions (one Poisson solve each), so that level lines still meet across the seams.
Status ScaleLevelSets(double factor, double h, LevelSetSolution* solution) {
  LevelSetSeams& seams = solution->seams;
  if (!seams.cut) {
    for (double& value : solution->phi) value *= factor;
    for (double& value : solution->psi) value *= factor;
    return Status::Ok();
  }
  const SurfaceModel& s = seams.cut->cut();
  const LevelSetGeometry geo = Precompute(s);
  for (int family = 0; family < 2; ++family) {
    std::vector<double>& u = family == 0 ? solution->phi_cut : solution->psi_cut;
    std::vector<double>& offsets = family == 0 ? seams.phi_offset : seams.psi_offset;
    std::vector<Eigen::Vector3d> target(s.num_faces());
    for (int f = 0; f < s.num_faces(); ++f) target[f] = factor * Gradient(geo, s, f, u);
    for (double& a : offsets) a *= factor;
    RoundOffsets(seams, &offsets);
    PQ_RETURN_IF_ERROR(PoissonFit(s, geo, target, std::vector<double>(s.num_faces(), 1.0), &u, &seams, family, false, h));
    ProjectTransitions(seams, offsets, &u);
  }
  solution->phi = seams.cut->ToOriginal(solution->phi_cut);
  solution->psi = seams.cut->ToOriginal(solution->psi_cut);
  return Status::Ok();
}

}  // namespace

Status RunLevelsetStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  SurfaceModel& surface = *state->surface;
  LevelSetSolution& solution = state->levelsets;
  const double h = state->config.layout.spacing;
  PQ_RETURN_IF_ERROR(SolveLevelSets(surface, state->guidance, state->config.levelset, h, &solution));
  const SeamCut* seams = solution.seams.cut.get();
  const SurfaceModel& level_surface = seams != nullptr ? seams->cut() : surface;
  const std::vector<double>& phi_values = seams != nullptr ? solution.phi_cut : solution.phi;
  const std::vector<double>& psi_values = seams != nullptr ? solution.psi_cut : solution.psi;
  double density_scale = 1.0;
  if (state->config.layout.density == "panel_area") {
    density_scale = PanelAreaScale(level_surface, phi_values, psi_values, h);
    PQ_RETURN_IF_ERROR(ScaleLevelSets(density_scale, h, &solution));
    LOG(INFO) << "levelset: φ and ψ scaled by " << density_scale << " for a mean panel area of h²";
  }
  auto phi = surface.VertexField<double>("phi");
  auto psi = surface.VertexField<double>("psi");
  for (int v = 0; v < surface.num_vertices(); ++v) {
    phi[VertexHandle(v)] = solution.phi[v];
    psi[VertexHandle(v)] = solution.psi[v];
  }
  *metrics = solution.metrics.ToJson();
  (*metrics)["initial_guess"] = solution.initial.ToJson();
  (*metrics)["ceres"] = solution.solver;
  (*metrics)["working_mesh_triangles"] = solution.working_faces;
  (*metrics)["density_scale"] = density_scale;
  (*metrics)["seams"] = solution.seams.ToJson();
  PQ_RETURN_IF_ERROR(WriteCsvTable({"id", "phi", "psi"}, {&solution.phi, &solution.psi}, out->Path("fields/levelsets.csv")));
  PQ_RETURN_IF_ERROR(WriteSurfaceFieldsVtk(*state, out));
  const auto& m = solution.metrics;
  LOG(INFO) << "levelset: alignment " << m.alignment_rms_deg << "° RMS (" << m.alignment_rms_deg_strong
            << "° where weight > 0.5), spacing CV φ " << m.spacing_cv_phi << " ψ " << m.spacing_cv_psi
            << ", conjugacy " << m.conjugacy_rms << ", min crossing " << m.min_crossing_angle_deg << "° ("
            << m.faces_below_min_angle << " faces below " << state->config.levelset.min_angle << "°), "
            << m.foldovers << " fold-overs";
  // The layout is still written, but the run must say that its quads are not what was asked for.
  if (m.foldovers > 0 || m.faces_below_min_angle > 0) {
    std::ostringstream what;
    what.precision(3);
    what << m.faces_below_min_angle << " faces (" << 100.0 * m.area_below_min_angle << " % of the area) cross below "
         << "levelset.min_angle " << state->config.levelset.min_angle << "° (the smallest at "
         << m.min_crossing_angle_deg << "°): the quads there are sheared";
    if (m.foldovers > 0) what << "; " << m.foldovers << " faces fold over: the quads there are inverted";
    LOG(WARNING) << "levelset: " << what.str();
  }
  PQ_RETURN_IF_ERROR(WriteLevelSetFigure(surface, phi_values, psi_values, h, state->guidance.direction,
                                         state->guidance.weight,
                                         "Level sets: φ (black) aligned with the guidance, ψ (blue) conjugate",
                                         out->Path("figures/levelsets.svg"), {}, seams));
  return Status::Ok();
}

}  // namespace pqlayout
