// Stage `stiffen`, the optimiser: see problems/stiffen.h.
#include "problems/stiffen.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <tuple>

#include "geometry/closest_point.h"
#include "geometry/interrupt.h"
#include "geometry/planarity.h"
#include "problems/grid_frame.h"
#include "problems/residuals/edge_length_residual.h"
#include "problems/residuals/fairness_change_residual.h"
#include "problems/residuals/planarity_budget_residual.h"
#include "problems/residuals/proximal_step_residual.h"
#include "solver/ceres_options.h"
#include "solver/framed_point_cost.h"

namespace pqlayout {

namespace {
// Faces smaller than this × the mean face area (boundary slivers between two nearly
// coinciding boundary points) have no meaningful normal: their kinks are not counted.
constexpr double kSliverArea = 0.01;
}  // namespace

nlohmann::json StiffenReport::ToJson() const {
  return {{"compliance_before", compliance_before},
          {"compliance_after", compliance_after},
          {"compliance_ratio", compliance_ratio},
          {"offset_max", offset_max},
          {"offset_mean", offset_mean},
          {"displacement_max", displacement_max},
          {"planarity_max", planarity_max},
          {"closeness_max", closeness_max},
          {"kink_mean_deg_before", kink_mean_deg_before},
          {"kink_max_deg_before", kink_max_deg_before},
          {"kink_mean_deg", kink_mean_deg_after},
          {"kink_max_deg", kink_max_deg_after},
          {"steel_mass_change", steel_mass_change},
          {"min_member_length", min_member_length},
          {"iterations", iterations},
          {"evaluations", evaluations},
          {"rejected_steps", rejected_steps},
          {"held_vertices", held_vertices},
          {"frame_seconds", seconds_frame},
          {"ceres_seconds", seconds_ceres}};
}

std::vector<double> KinkAngles(const PolyMesh& mesh) {
  std::vector<Eigen::Vector3d> normal(mesh.n_faces(), Eigen::Vector3d::Zero());
  std::vector<double> area(mesh.n_faces(), 0.0);
  double mean_area = 0.0;
  for (const auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (const auto v : mesh.fv_range(f)) p.push_back(ToEigen(mesh.point(v)));
    for (size_t k = 0; k < p.size(); ++k) normal[f.idx()] += p[k].cross(p[(k + 1) % p.size()]);
    area[f.idx()] = 0.5 * normal[f.idx()].norm();
    mean_area += area[f.idx()] / mesh.n_faces();
    normal[f.idx()].normalize();
  }
  std::vector<double> angles;
  for (const auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    const int f = mesh.face_handle(mesh.halfedge_handle(e, 0)).idx(), g = mesh.face_handle(mesh.halfedge_handle(e, 1)).idx();
    if (area[f] < kSliverArea * mean_area || area[g] < kSliverArea * mean_area) continue;
    angles.push_back(std::atan2(normal[f].cross(normal[g]).norm(), normal[f].dot(normal[g])) * 180.0 / M_PI);
  }
  return angles;
}

namespace {

// The schedule (problems/stiffen.h).
constexpr double kPlanarityStart = 1e6;   // × stiffen.weights.planarity; r ≈ √w δ
constexpr double kPlanarityRaise = 10.0;  // until a step meets δ ≤ kPlanarityMargin × target
constexpr int kMaxPlanarityRaises = 6;
constexpr double kPlanarityMargin = 0.9;
// The per-vertex budget (PlanarityBudgetResidual's ε) starts at this × δ target / 2 (a quad
// ±e off its plane has δ = 2e/ℓ) and shrinks ×0.7 with every raise after the second, for the
// n-gons and skew quads where the plane distance understates δ.
constexpr double kBudgetStart = 0.8, kBudgetShrink = 0.7;
constexpr int kCeresIterations = 50;      // per step (the step problem is nearly linear)
constexpr double kFirstStep = 0.3;        // the first step's unconstrained length, × tolerance
constexpr double kGrow = 1.5, kShrink = 0.3;
constexpr double kStopDecrease = 1e-5;    // relative decrease of F below which a step counts as small
constexpr int kSmallSteps = 5;            // ... and this many small steps in a row end the stage
constexpr double kMinStep = 1e-4;         // so does μ below this × its first value (steps keep failing)
constexpr double kMinMemberOfDepth = 1.1; // members ≥ 1.1 × section depth

using Vec3 = Eigen::Vector3d;

struct Problem {
  // Variables: per vertex, local coordinates q in its frame (p = f + R q) with box bounds.
  std::vector<PointFrame> frames;
  std::vector<Vec3> lower, upper;
  std::vector<bool> held;
  // Fixed data of the planarised mesh.
  std::vector<std::vector<int>> faces;
  std::vector<double> mean_diagonal;
  std::vector<std::array<int, 3>> triples;   // mesh polylines a–v–b at valence-4 interior vertices
  std::vector<Vec3> second_difference0;      // their planarised second differences
  std::vector<std::tuple<int, int, double>> members;  // (i, j, minimum length)
  double h = 1.0, beta = 0.0;
  StiffenWeights weights;
};

std::vector<Vec3> World(const Problem& P, const std::vector<Vec3>& q) {
  std::vector<Vec3> x(q.size());
  for (size_t v = 0; v < q.size(); ++v) x[v] = P.frames[v].ToWorld(q[v]);
  return x;
}

void SetPoints(const std::vector<Vec3>& x, PolyMesh* mesh) {
  for (size_t v = 0; v < x.size(); ++v) mesh->set_point(VertexHandle(static_cast<int>(v)), {x[v].x(), x[v].y(), x[v].z()});
}

Vec3 SecondDifference(const std::vector<Vec3>& x, const std::array<int, 3>& t) { return x[t[0]] - 2.0 * x[t[1]] + x[t[2]]; }

double MaxPlanarity(const Problem& P, const std::vector<Vec3>& x) {
  double delta = 0.0;
  std::vector<Vec3> polygon;
  for (const auto& face : P.faces) {
    polygon.clear();
    for (const int v : face) polygon.push_back(x[v]);
    delta = std::max(delta, PlanarityDelta(polygon));
  }
  return delta;
}

// The least-squares parts of F (½ Σ r² of the fairness-change and member-hinge residuals).
double Penalties(const Problem& P, const std::vector<Vec3>& x) {
  double sum = 0.0;
  for (size_t t = 0; t < P.triples.size(); ++t)
    sum += 0.5 * P.weights.fairness * (SecondDifference(x, P.triples[t]) - P.second_difference0[t]).squaredNorm() / (P.h * P.h);
  for (const auto& [i, j, min_length] : P.members) {
    const double short_by = std::max(0.0, min_length - (x[i] - x[j]).norm()) / P.h;
    sum += 0.5 * P.weights.edge_length * short_by * short_by;
  }
  return sum;
}

// Each vertex's frame (tangents and normal of the reference at the foot point of its
// planarised position) and box (header). Vertices that cannot move are held.
void SetUpVariables(const ClosestPointQuery& query, const ExtractedMesh& mesh, const GridFrame& frame,
                    const StiffenOptions& o, Problem* P, std::vector<Vec3>* q) {
  const int n = static_cast<int>(mesh.mesh.n_vertices());
  P->frames.resize(n), P->lower.resize(n), P->upper.resize(n), P->held.assign(n, false), q->resize(n);
  const double t = o.tolerance * (1.0 - 1e-9);
  for (int v = 0; v < n; ++v) {
    const Vec3 p = ToEigen(mesh.mesh.point(VertexHandle(v)));
    const SurfacePoint foot = query.OnSurface(p);
    const Vec3 normal = foot.normal.normalized();
    const Vec3 e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
    PointFrame& f = P->frames[v];
    f.origin = foot.point;
    f.rotation.col(0) = e1, f.rotation.col(1) = e2, f.rotation.col(2) = normal;
    Vec3& local = (*q)[v] = f.ToLocal(p);
    const double a = std::abs(local[0]) + o.slide, b = std::abs(local[1]) + o.slide;
    const double normal_room = t * t - a * a - b * b;
    P->held[v] = mesh.origin[v].on_boundary || mesh.origin[v].corner || frame.node_size[frame.node_of[v]] > 1 ||
                 normal_room <= 0.0;
    if (P->held[v]) {
      f.origin = p, f.rotation.setIdentity(), local.setZero();  // exactly where it is
      continue;
    }
    const double s = std::sqrt(normal_room);
    P->lower[v] = Vec3(local[0] - o.slide, local[1] - o.slide, -s);
    P->upper[v] = Vec3(local[0] + o.slide, local[1] + o.slide, s);
    local[2] = std::clamp(local[2], -s, s);  // a planarised vertex farther than t comes in
  }
}

void SetUpData(const ExtractedMesh& mesh, const GridFrame& frame, const SectionOptions& section,
               const StiffenOptions& o, const std::vector<Vec3>& x0, Problem* P) {
  const PolyMesh& m = mesh.mesh;
  for (const auto f : m.faces()) {
    std::vector<int> ids;
    std::vector<Vec3> polygon;
    for (const auto v : m.fv_range(f)) ids.push_back(v.idx()), polygon.push_back(x0[v.idx()]);
    P->faces.push_back(ids);
    P->mean_diagonal.push_back(FitPolygonPlane(polygon).mean_diagonal);
  }
  for (const auto v : m.vertices()) {
    if (m.is_boundary(v) || m.valence(v) != 4) continue;
    std::vector<int> ring;
    for (const auto w : m.vv_range(v)) ring.push_back(w.idx());
    P->triples.push_back({ring[0], v.idx(), ring[2]});
    P->triples.push_back({ring[1], v.idx(), ring[3]});
  }
  for (const auto& t : P->triples) P->second_difference0.push_back(SecondDifference(x0, t));
  for (const auto& [i, j] : frame.member_vertices) {
    const double length = (x0[i] - x0[j]).norm();
    P->members.emplace_back(i, j, std::min(length, std::max(kMinMemberOfDepth * SectionDepth(section), o.min_member * length)));
  }
}

ceres::CostFunction* Framed(const Problem& P, ceres::CostFunction* inner, std::initializer_list<int> vertices,
                            bool leading_plane = false) {
  std::vector<const PointFrame*> frames;
  if (leading_plane) frames.push_back(nullptr);
  for (const int v : vertices) frames.push_back(&P.frames[v]);
  return new FramedPointCost(inner, frames);
}

// One step from q (in place): the Ceres problem of the header with step length mu.
Status SolveStep(const Problem& P, const std::vector<Vec3>& gradient, double mu, double planarity_weight,
                 double planarity_budget, std::vector<Vec3>* q, ceres::Solver::Summary* summary) {
  const std::vector<Vec3> xk = World(P, *q);
  ceres::Problem problem;
  const int n = static_cast<int>(q->size());
  for (int v = 0; v < n; ++v) {
    double* block = (*q)[v].data();
    problem.AddParameterBlock(block, 3);
    if (P.held[v]) {
      problem.SetParameterBlockConstant(block);
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      problem.SetParameterLowerBound(block, k, P.lower[v][k]);
      problem.SetParameterUpperBound(block, k, P.upper[v][k]);
    }
    problem.AddResidualBlock(Framed(P, ProximalStepResidual::Create(xk[v] - mu * gradient[v], mu), {v}), nullptr, block);
  }
  std::vector<std::array<double, 4>> planes(P.faces.size());
  for (size_t f = 0; f < P.faces.size(); ++f) {
    if (P.faces[f].size() < 4) continue;
    std::vector<Vec3> polygon;
    for (const int v : P.faces[f]) polygon.push_back(xk[v]);
    const FacePlane plane = FitPolygonPlane(polygon);
    planes[f] = {plane.n.x(), plane.n.y(), plane.n.z(), plane.d};
    problem.AddParameterBlock(planes[f].data(), 4,
                              new ceres::ProductManifold<ceres::SphereManifold<3>, ceres::EuclideanManifold<1>>());
    for (const int v : P.faces[f])
      problem.AddResidualBlock(
          Framed(P, PlanarityBudgetResidual::Create(planarity_weight, P.mean_diagonal[f], planarity_budget), {v}, true),
          nullptr, planes[f].data(), (*q)[v].data());
  }
  for (size_t t = 0; t < P.triples.size(); ++t) {
    const auto& [a, v, b] = P.triples[t];
    if (P.held[a] && P.held[v] && P.held[b]) continue;
    double* blocks[3] = {(*q)[a].data(), (*q)[v].data(), (*q)[b].data()};
    if (P.beta > 0.0)
      problem.AddResidualBlock(
          Framed(P, FairnessChangeResidual::Create(SecondDifference(xk, P.triples[t]), P.beta * P.h * P.h / mu, P.h), {a, v, b}),
          nullptr, blocks[0], blocks[1], blocks[2]);
    if (P.weights.fairness > 0.0)
      problem.AddResidualBlock(
          Framed(P, FairnessChangeResidual::Create(P.second_difference0[t], P.weights.fairness, P.h), {a, v, b}), nullptr,
          blocks[0], blocks[1], blocks[2]);
  }
  if (P.weights.edge_length > 0.0)
    for (const auto& [i, j, min_length] : P.members) {
      if (P.held[i] && P.held[j]) continue;
      problem.AddResidualBlock(Framed(P, EdgeLengthResidual::Create(min_length, P.weights.edge_length, P.h), {i, j}),
                               nullptr, (*q)[i].data(), (*q)[j].data());
    }
  ceres::Solve(SparseCholeskyOptions(kCeresIterations), &problem, summary);
  if (!summary->IsSolutionUsable()) return Status::Internal("stiffen: Ceres failed: " + summary->message);
  return CheckInterrupt();
}

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

namespace {

// The state of the iteration at an accepted point.
struct Iterate {
  std::vector<Vec3> q;
  GridCompliance eval;
  double merit = 0.0;  // F = C/C₀ + penalties
};

Status Evaluate(const Problem& P, const std::vector<Restraints>& restraints, const AnalysisOptions& analysis,
                double c0, PolyMesh* mesh, Iterate* it, StiffenReport* report) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Vec3> x = World(P, it->q);
  SetPoints(x, mesh);
  const Status status = EvaluateGridCompliance(*mesh, restraints, analysis, true, &it->eval);
  report->seconds_frame += Seconds(start);
  ++report->evaluations;
  PQ_RETURN_IF_ERROR(status);
  it->merit = it->eval.compliance / c0 + Penalties(P, x);
  return Status::Ok();
}

void Measure(const Problem& P, const ClosestPointQuery& query, const std::vector<Vec3>& x0, const Iterate& first,
             const Iterate& last, PolyMesh* mesh, StiffenReport* r) {
  const std::vector<Vec3> x = World(P, last.q);
  r->compliance_before = first.eval.compliance;
  r->compliance_after = last.eval.compliance;
  r->compliance_ratio = r->compliance_after / r->compliance_before;
  r->steel_mass_change = last.eval.frame.steel_mass / first.eval.frame.steel_mass - 1.0;
  r->planarity_max = MaxPlanarity(P, x);
  r->normal_offset.assign(x.size(), 0.0);
  r->closeness_max = r->offset_max = r->offset_mean = r->displacement_max = 0.0;
  for (size_t v = 0; v < x.size(); ++v) {
    r->closeness_max = std::max(r->closeness_max, query.OnSurface(x[v]).distance);
    const Vec3 normal = P.held[v] ? query.OnSurface(x0[v]).normal : Vec3(P.frames[v].rotation.col(2));
    r->normal_offset[v] = (x[v] - x0[v]).dot(normal);
    r->offset_max = std::max(r->offset_max, std::abs(r->normal_offset[v]));
    r->offset_mean += std::abs(r->normal_offset[v]) / x.size();
    r->displacement_max = std::max(r->displacement_max, (x[v] - x0[v]).norm());
  }
  r->min_member_length = std::numeric_limits<double>::infinity();
  for (const auto& [i, j, min_length] : P.members) r->min_member_length = std::min(r->min_member_length, (x[i] - x[j]).norm());
  SetPoints(x, mesh);
  const std::vector<double> kinks = KinkAngles(*mesh);
  r->kink_mean_deg_after = r->kink_max_deg_after = 0.0;
  for (const double k : kinks) r->kink_mean_deg_after += k / kinks.size(), r->kink_max_deg_after = std::max(r->kink_max_deg_after, k);
}

// Limited-memory BFGS (Nocedal & Wright, Algorithm 7.4) on the free vertices' positions:
// the step direction −H g of the compliance, H from the last kMemory accepted steps. The
// compliance is ill-conditioned (a grid shell is far stiffer in membrane action than in
// bending), so plain gradient steps crawl; the numpy prototype used L-BFGS-B for the same reason.
class Lbfgs {
 public:
  explicit Lbfgs(const std::vector<bool>& held) : held_(held) {}

  std::vector<Vec3> Gradient(const std::vector<Vec3>& dc, double c0) const {
    std::vector<Vec3> g(dc.size());
    for (size_t v = 0; v < g.size(); ++v) g[v] = held_[v] ? Vec3::Zero() : Vec3(dc[v] / c0);
    return g;
  }
  bool empty() const { return s_.empty(); }
  void Clear() { s_.clear(), y_.clear(), rho_.clear(); }
  // Adds the pair (x₁ − x₀, g₁ − g₀) if its curvature is positive; true if it is the first.
  bool Add(const std::vector<Vec3>& x0, const std::vector<Vec3>& x1, const std::vector<Vec3>& g0,
           const std::vector<Vec3>& g1) {
    Eigen::VectorXd s(3 * x0.size()), y(3 * x0.size());
    for (size_t v = 0; v < x0.size(); ++v)
      s.segment<3>(3 * v) = held_[v] ? Vec3::Zero() : Vec3(x1[v] - x0[v]), y.segment<3>(3 * v) = g1[v] - g0[v];
    const double sy = s.dot(y);
    if (!(sy > 1e-12 * s.norm() * y.norm())) return false;
    const bool first = s_.empty();
    s_.push_back(s), y_.push_back(y), rho_.push_back(1.0 / sy);
    if (s_.size() > kMemory) s_.erase(s_.begin()), y_.erase(y_.begin()), rho_.erase(rho_.begin());
    return first;
  }
  // H g (the step is −μ H g); g itself while there is no pair.
  std::vector<Vec3> Direction(const std::vector<Vec3>& g) const {
    Eigen::VectorXd q(3 * g.size());
    for (size_t v = 0; v < g.size(); ++v) q.segment<3>(3 * v) = g[v];
    std::vector<double> alpha(s_.size());
    for (int k = static_cast<int>(s_.size()) - 1; k >= 0; --k) alpha[k] = rho_[k] * s_[k].dot(q), q -= alpha[k] * y_[k];
    if (!s_.empty()) q *= s_.back().dot(y_.back()) / y_.back().squaredNorm();
    for (size_t k = 0; k < s_.size(); ++k) q += s_[k] * (alpha[k] - rho_[k] * y_[k].dot(q));
    std::vector<Vec3> d(g.size());
    for (size_t v = 0; v < g.size(); ++v) d[v] = q.segment<3>(3 * v);
    return d;
  }

 private:
  static constexpr size_t kMemory = 8;
  const std::vector<bool>& held_;
  std::vector<Eigen::VectorXd> s_, y_;
  std::vector<double> rho_;
};

// The planarity penalty's weight and budget, raised / shrunk as steps need it.
struct StepSchedule {
  double weight, budget;
};

// One step from q to *trial along −μ d, the planarity weight raised (and, after the
// second raise, the budget shrunk) until δ max ≤ kPlanarityMargin × target or the raises
// are spent; *delta is the step's δ max.
Status PlanarStep(const Problem& P, const std::vector<Vec3>& d, double mu, double target_delta, StepSchedule* schedule,
                  const std::vector<Vec3>& q, std::vector<Vec3>* trial, double* delta, ceres::Solver::Summary* summary,
                  StiffenReport* report) {
  for (int raise = 0; raise <= kMaxPlanarityRaises; ++raise) {
    *trial = q;
    const auto start = std::chrono::steady_clock::now();
    PQ_RETURN_IF_ERROR(SolveStep(P, d, mu, schedule->weight, schedule->budget, trial, summary));
    report->seconds_ceres += Seconds(start);
    *delta = MaxPlanarity(P, World(P, *trial));
    if (*delta <= kPlanarityMargin * target_delta) return Status::Ok();
    schedule->weight *= kPlanarityRaise;
    if (raise >= 2) schedule->budget *= kBudgetShrink;
  }
  return Status::Ok();
}

}  // namespace

Status StiffenMesh(const SurfaceModel& reference, const std::vector<Restraints>& restraints,
                   const AnalysisOptions& analysis, const StiffenOptions& options, double target_delta, double h,
                   ExtractedMesh* mesh, StiffenReport* report) {
  const std::vector<double> kinks = KinkAngles(mesh->mesh);
  for (const double k : kinks)
    report->kink_mean_deg_before += k / kinks.size(), report->kink_max_deg_before = std::max(report->kink_max_deg_before, k);
  std::vector<Vec3> x0(mesh->mesh.n_vertices());
  for (const auto v : mesh->mesh.vertices()) x0[v.idx()] = ToEigen(mesh->mesh.point(v));
  const ClosestPointQuery query(reference);
  Problem P;
  P.h = h;
  P.beta = std::pow(options.smoothing, 4.0);  // (ℓ/h)⁴ with ℓ = smoothing × h
  P.weights = options.weights;
  Iterate current;
  GridFrame frame;
  BuildGridFrame(mesh->mesh, restraints, analysis, &frame);
  SetUpVariables(query, *mesh, frame, options, &P, &current.q);
  SetUpData(*mesh, frame, analysis.section, options, x0, &P);
  for (const bool held : P.held) report->held_vertices += held;
  PQ_RETURN_IF_ERROR(Evaluate(P, restraints, analysis, 1.0, &mesh->mesh, &current, report).WithContext("stiffen"));
  const double c0 = current.eval.compliance;
  current.merit = 1.0 + Penalties(P, World(P, current.q));
  const Iterate first = current;
  if (options.tolerance == 0.0 || options.max_iterations == 0) {
    Measure(P, query, x0, first, current, &mesh->mesh, report);
    return Status::Ok();
  }
  Lbfgs lbfgs(P.held);
  std::vector<Vec3> g = lbfgs.Gradient(current.eval.gradient, c0);
  double g_max = 0.0;
  for (const auto& gv : g) g_max = std::max(g_max, gv.norm());
  // Until the first curvature pair, steps along −g of kFirstStep × tolerance at most; then
  // quasi-Newton steps, μ = 1 the natural length.
  double mu = g_max > 0.0 ? kFirstStep * options.tolerance / g_max : 0.0;
  const double first_mu = mu;
  std::vector<Vec3> d = g;
  const double mu_min = kMinStep * mu;
  StepSchedule schedule{kPlanarityStart * options.weights.planarity, kBudgetStart * target_delta / 2.0};
  const int joints = frame.joints;
  int small_steps = 0;
  for (report->iterations = 0; report->iterations < options.max_iterations && small_steps < kSmallSteps && mu > mu_min;
       ++report->iterations) {
    Iterate trial;
    ceres::Solver::Summary summary;
    double delta = 0.0;
    PQ_RETURN_IF_ERROR(PlanarStep(P, d, mu, target_delta, &schedule, current.q, &trial.q, &delta, &summary, report));
    const bool planar = delta <= kPlanarityMargin * target_delta;
    const Status evaluated = planar ? Evaluate(P, restraints, analysis, c0, &mesh->mesh, &trial, report) : Status::Ok();
    const bool accepted = planar && evaluated.ok() && trial.eval.frame.joints == joints && trial.merit < current.merit;
    const double decrease = accepted ? (current.merit - trial.merit) / current.merit : 0.0;
    if (accepted) {
      std::vector<Vec3> g_new = lbfgs.Gradient(trial.eval.gradient, c0);
      const bool first_pair = lbfgs.Add(World(P, current.q), World(P, trial.q), g, g_new);
      g = g_new;
      d = lbfgs.Direction(g);
      current = std::move(trial);
      mu = first_pair ? 1.0 : std::min(lbfgs.empty() ? kGrow * mu : 1.0, kGrow * mu);
    } else if (!lbfgs.empty()) {  // the quasi-Newton model misled the step: restart from the gradient
      lbfgs.Clear();
      d = g;
      mu = first_mu;
      ++report->rejected_steps;
    } else {
      mu *= kShrink;
      ++report->rejected_steps;
    }
    small_steps = accepted && decrease < kStopDecrease ? small_steps + 1 : accepted ? 0 : small_steps;
    LOG(INFO) << "stiffen: iteration " << report->iterations + 1 << (accepted ? "" : " (rejected)") << ": C/C₀ "
              << current.eval.compliance / c0 << ", F " << current.merit << ", δ max " << delta << ", next μ " << mu
              << " (" << summary.iterations.size() - 1 << " Ceres iterations)";
  }
  Measure(P, query, x0, first, current, &mesh->mesh, report);
  return Status::Ok();
}

}  // namespace pqlayout
