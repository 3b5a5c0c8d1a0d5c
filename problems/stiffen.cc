// Stage `stiffen`, the optimiser: see problems/stiffen.h.
#include "problems/stiffen.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "geometry/closest_point.h"
#include "geometry/interrupt.h"
#include "geometry/planarity.h"
#include "problems/grid_frame.h"
#include "problems/residuals/edge_length_residual.h"
#include "problems/residuals/fairness_change_residual.h"
#include "problems/residuals/joint_length_residual.h"
#include "problems/residuals/planarity_lagrangian_residual.h"
#include "problems/stiffen_problem.h"
#include "solver/ceres_options.h"
#include "solver/cholmod_solver.h"

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

using Vec3 = Eigen::Vector3d;

// The schedule (problems/stiffen.h).
constexpr double kPlanarityMargin = 0.9;  // the constraint is δ ≤ 0.9 × planarize.target_delta
constexpr double kPenaltyStart = 1e4;     // ρ × (δ excess)² against C/C₀ ~ 1 (× stiffen.weights.planarity)
constexpr double kPenaltyRaise = 10.0;    // when a round cut the violation by less than kViolationCut
constexpr double kViolationCut = 0.25;
constexpr double kPenaltyMax = 1e9;       // beyond, L-BFGS stalls on the conditioning
constexpr double kRoundGain = 1e-3;       // a feasible round that lowers L by less than this (relative) ends the stage
constexpr double kFeasible = 0.02;        // a violation below this × δ_allowed counts as met (δ ≤ 0.918 × target)
constexpr double kJointWeight = 1e4;      // joints stay joints (the frame's topology is fixed)
constexpr int kRounds = 20;               // multiplier updates at most
constexpr int kRoundIterations = 100;     // L-BFGS iterations per round at most

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// L(z) = C(x)/C₀ + fairness change + member hinge + Σ PHR planarity terms, x = f + R q,
// q = centre + radius ∘ sin z per vertex (the box, smoothly; held vertices are not in z).
// Penalty terms are Ceres residual blocks on the world positions, evaluated with their
// gradient by ceres::Problem::Evaluate; C and ∇C by the adjoint (problems/grid_frame.h).
class Lagrangian final : public ceres::FirstOrderFunction {
 public:
  Lagrangian(const StiffenProblem& P, const std::vector<Restraints>& restraints, const AnalysisOptions& analysis,
             double c0, int joints, double allowed, PolyMesh* mesh, StiffenReport* report)
      : P_(P), restraints_(restraints), analysis_(analysis), c0_(c0), joints_(joints), allowed_(allowed), mesh_(mesh),
        report_(report) {
    for (size_t v = 0; v < P.held.size(); ++v)
      if (!P.held[v]) free_.push_back(static_cast<int>(v));
    positions_.resize(P.held.size());
    lambda_.assign(P.sub_quads.size(), 0.0);
    ceres::Problem::Options options;
    options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    penalties_ = std::make_unique<ceres::Problem>(options);
    for (auto& p : positions_) penalties_->AddParameterBlock(p.data(), 3);
    for (size_t v = 0; v < P.held.size(); ++v)
      if (P.held[v]) penalties_->SetParameterBlockConstant(positions_[v].data());
    for (size_t k = 0; k < P.sub_quads.size(); ++k) {
      const auto& s = P.sub_quads[k];
      if (P.held[s[0]] && P.held[s[1]] && P.held[s[2]] && P.held[s[3]]) continue;
      penalties_->AddResidualBlock(PlanarityLagrangianResidual::Create(&lambda_[k], &rho_, allowed_), nullptr,
                                   Block(s[0]), Block(s[1]), Block(s[2]), Block(s[3]));
    }
    for (size_t t = 0; t < P.triples.size(); ++t) {
      const auto& [a, v, b] = P.triples[t];
      if (P.weights.fairness > 0.0 && !(P.held[a] && P.held[v] && P.held[b]))
        penalties_->AddResidualBlock(FairnessChangeResidual::Create(P.second_difference0[t], P.weights.fairness, P.h),
                                     nullptr, Block(a), Block(v), Block(b));
    }
    for (const auto& [i, j, min_length] : P.members)
      if (P.weights.edge_length > 0.0 && !(P.held[i] && P.held[j]))
        penalties_->AddResidualBlock(EdgeLengthResidual::Create(min_length, P.weights.edge_length, P.h), nullptr,
                                     Block(i), Block(j));
    for (const auto& [i, j, max_length] : P.joint_edges)
      if (!(P.held[i] && P.held[j]))
        penalties_->AddResidualBlock(JointLengthResidual::Create(max_length, kJointWeight, P.h), nullptr,
                                     Block(i), Block(j));
    for (const int v : free_) evaluate_options_.parameter_blocks.push_back(Block(v));
  }

  int NumParameters() const override { return 3 * static_cast<int>(free_.size()); }

  void SetPenalty(double rho) { rho_ = rho; }
  double allowed() const { return allowed_; }
  const StiffenProblem& problem() const { return P_; }
  double rho() const { return rho_; }

  // q of every vertex from z (held vertices keep q_start).
  std::vector<Vec3> Local(const double* z, const std::vector<Vec3>& q_start) const {
    std::vector<Vec3> q = q_start;
    for (size_t k = 0; k < free_.size(); ++k) {
      const int v = free_[k];
      for (int c = 0; c < 3; ++c)
        q[v][c] = Centre(v, c) + Radius(v, c) * std::sin(z[3 * k + c]);
    }
    return q;
  }
  // z of q (inverse of Local).
  std::vector<double> Parameters(const std::vector<Vec3>& q) const {
    std::vector<double> z(3 * free_.size(), 0.0);
    for (size_t k = 0; k < free_.size(); ++k)
      for (int c = 0; c < 3; ++c) {
        const int v = free_[k];
        const double radius = Radius(v, c);
        z[3 * k + c] = radius > 0.0 ? std::asin(std::clamp((q[v][c] - Centre(v, c)) / radius, -1.0, 1.0)) : 0.0;
      }
    return z;
  }

  // λ ← max(0, λ + ρ g) for every sub-quad at x; returns the largest violation max(0, δ − δ_allowed).
  double UpdateMultipliers(const std::vector<Vec3>& x) {
    double violation = 0.0;
    for (size_t k = 0; k < P_.sub_quads.size(); ++k) {
      const auto& s = P_.sub_quads[k];
      const double g = QuadPlanarityDelta(x[s[0]], x[s[1]], x[s[2]], x[s[3]]) - allowed_;
      lambda_[k] = std::max(0.0, lambda_[k] + rho_ * g);
      violation = std::max(violation, g);
    }
    return violation;
  }

  bool Evaluate(const double* z, double* cost, double* gradient) const override;

 private:
  double* Block(int v) { return positions_[v].data(); }
  double Centre(int v, int c) const { return 0.5 * (P_.lower[v][c] + P_.upper[v][c]); }
  double Radius(int v, int c) const { return 0.5 * (P_.upper[v][c] - P_.lower[v][c]); }

  const StiffenProblem& P_;
  const std::vector<Restraints>& restraints_;
  const AnalysisOptions& analysis_;
  const double c0_;
  const int joints_;
  const double allowed_;  // δ_allowed of every sub-quad
  PolyMesh* mesh_;
  StiffenReport* report_;
  std::vector<int> free_;
  mutable std::vector<Vec3> positions_;  // the penalty problem's parameter blocks (world)
  std::vector<double> lambda_;
  double rho_ = kPenaltyStart;
  std::unique_ptr<ceres::Problem> penalties_;
  ceres::Problem::EvaluateOptions evaluate_options_;
  mutable CholmodSolver solver_;  // keeps the frame's symbolic analysis across evaluations
};

// ceres::GradientProblem owns its function; the Lagrangian outlives the rounds, so each
// round gets this non-owning forwarder.
class Borrowed final : public ceres::FirstOrderFunction {
 public:
  explicit Borrowed(const ceres::FirstOrderFunction& f) : f_(f) {}
  bool Evaluate(const double* z, double* cost, double* gradient) const override { return f_.Evaluate(z, cost, gradient); }
  int NumParameters() const override { return f_.NumParameters(); }

 private:
  const ceres::FirstOrderFunction& f_;
};

bool Lagrangian::Evaluate(const double* z, double* cost, double* gradient) const {
  std::vector<Vec3> q(P_.held.size(), Vec3::Zero());  // held vertices: q = 0 in the identity frame at p
  q = Local(z, q);
  const std::vector<Vec3> x = World(P_, q);
  for (size_t v = 0; v < x.size(); ++v) positions_[v] = x[v];
  double penalty = 0.0;
  std::vector<double> penalty_gradient;
  if (!penalties_->Evaluate(evaluate_options_, &penalty, nullptr, gradient ? &penalty_gradient : nullptr, nullptr))
    return false;
  const auto start = std::chrono::steady_clock::now();
  SetPoints(x, mesh_);
  GridCompliance c;
  const Status status = EvaluateGridCompliance(*mesh_, restraints_, analysis_, gradient != nullptr, &c, &solver_);
  report_->seconds_frame += Seconds(start);
  ++report_->evaluations;
  if (!status.ok() || c.frame.joints != joints_) return false;  // a mechanism, or a member became a joint
  *cost = c.compliance / c0_ + penalty;
  if (gradient == nullptr) return true;
  for (size_t k = 0; k < free_.size(); ++k) {
    const int v = free_[k];
    const Vec3 gx = c.gradient[v] / c0_ + Vec3(penalty_gradient[3 * k], penalty_gradient[3 * k + 1], penalty_gradient[3 * k + 2]);
    const Vec3 gq = P_.frames[v].rotation.transpose() * gx;
    for (int d = 0; d < 3; ++d) gradient[3 * k + d] = gq[d] * Radius(v, d) * std::cos(z[3 * k + d]);
  }
  return true;
}

void Measure(const StiffenProblem& P, const ClosestPointQuery& query, const std::vector<Vec3>& x0,
             const GridCompliance& first, const GridCompliance& last, const std::vector<Vec3>& q, PolyMesh* mesh,
             StiffenReport* r) {
  const std::vector<Vec3> x = World(P, q);
  r->compliance_before = first.compliance;
  r->compliance_after = last.compliance;
  r->compliance_ratio = r->compliance_after / r->compliance_before;
  r->steel_mass_change = last.frame.steel_mass / first.frame.steel_mass - 1.0;
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

// Rounds of L-BFGS (Ceres' GradientProblemSolver) on the Lagrangian, the multipliers updated
// and the penalty raised between them, until δ ≤ the allowed value and a round converges.
Status MinimiseLagrangian(Lagrangian* L, const StiffenOptions& options, std::vector<Vec3>* q, StiffenReport* report) {
  const std::vector<Vec3> q_start = *q;
  std::vector<double> z = L->Parameters(*q);
  double rho = kPenaltyStart * options.weights.planarity, previous = std::numeric_limits<double>::infinity();
  int budget = options.max_iterations;
  for (int round = 0; round < kRounds && budget > 0; ++round) {
    L->SetPenalty(rho);
    ceres::GradientProblem problem(new Borrowed(*L));
    ceres::GradientProblemSolver::Options solver_options;
    solver_options.max_num_iterations = std::min(budget, kRoundIterations);
    solver_options.function_tolerance = 1e-7;
    solver_options.logging_type = ceres::SILENT;
    InterruptCallback interrupt;
    solver_options.callbacks.push_back(&interrupt);
    ceres::GradientProblemSolver::Summary summary;
    const auto start = std::chrono::steady_clock::now();
    ceres::Solve(solver_options, problem, z.data(), &summary);
    report->seconds_ceres += Seconds(start);
    PQ_RETURN_IF_ERROR(CheckInterrupt());
    const int iterations = static_cast<int>(summary.iterations.size()) - 1;
    report->iterations += iterations, budget -= std::max(iterations, 1);
    *q = L->Local(z.data(), q_start);
    const double violation = L->UpdateMultipliers(World(L->problem(), *q));
    LOG(INFO) << "stiffen: round " << round + 1 << ": " << iterations << " L-BFGS iterations, L " << summary.initial_cost << " → " << summary.final_cost
              << ", δ max above " << L->allowed() << " by " << violation << ", ρ " << rho;
    const bool feasible = violation <= kFeasible * L->allowed();
    const bool stalled = summary.initial_cost - summary.final_cost < kRoundGain * summary.initial_cost;
    if (feasible && (summary.termination_type == ceres::CONVERGENCE || iterations <= 1 || stalled)) break;
    if (iterations == 0) break;  // the line search found no descent: more ρ only makes it worse
    if (!feasible && violation > kViolationCut * previous) rho = std::min(kPenaltyMax, rho * kPenaltyRaise);
    previous = violation;
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
  GridFrame frame;
  BuildGridFrame(mesh->mesh, restraints, analysis, &frame);
  StiffenProblem P;
  std::vector<Vec3> q;
  SetUpStiffenProblem(query, *mesh, frame, analysis.section, options, h, &P, &q);
  for (const bool held : P.held) report->held_vertices += held;
  GridCompliance first;
  SetPoints(World(P, q), &mesh->mesh);
  PQ_RETURN_IF_ERROR(EvaluateGridCompliance(mesh->mesh, restraints, analysis, false, &first).WithContext("stiffen"));
  if (options.tolerance > 0.0 && options.max_iterations > 0 && report->held_vertices < static_cast<int>(x0.size())) {
    Lagrangian L(P, restraints, analysis, first.compliance, frame.joints, kPlanarityMargin * target_delta, &mesh->mesh,
                 report);
    PQ_RETURN_IF_ERROR(MinimiseLagrangian(&L, options, &q, report));
    PQ_RETURN_IF_ERROR(RestorePlanarity(P, target_delta, &q));
  }
  GridCompliance last;
  SetPoints(World(P, q), &mesh->mesh);
  PQ_RETURN_IF_ERROR(EvaluateGridCompliance(mesh->mesh, restraints, analysis, false, &last).WithContext("stiffen"));
  Measure(P, query, x0, first, last, q, &mesh->mesh, report);
  return Status::Ok();
}

}  // namespace pqlayout
