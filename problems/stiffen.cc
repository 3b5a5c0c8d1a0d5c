// Stage `stiffen`, the optimiser: see problems/stiffen.h.
#include "problems/stiffen.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <deque>
#include <cmath>
#include <limits>
#include <memory>

#include "geometry/closest_point.h"
#include "base/interrupt.h"
#include "geometry/planarity.h"
#include "problems/grid_frame.h"
#include "problems/residuals/edge_length_residual.h"
#include "problems/residuals/fairness_change_residual.h"
#include "problems/residuals/joint_length_residual.h"
#include "problems/stiffen_manifold.h"
#include "problems/stiffen_problem.h"
#include "problems/structural_checks.h"
#include "solver/ceres_options.h"
#include "solver/block_cholesky.h"
#include "solver/cost_window.h"

namespace pqlayout {

namespace {
// Faces smaller than this × the mean face area (boundary slivers between two nearly
// coinciding boundary points) have no meaningful normal: their kinks are not counted.
constexpr double kSliverArea = 0.01;
}  // namespace

nlohmann::json StiffenReport::ToJson() const {
  // The checks are null when the stage is off (stiffen.tolerance = 0): their keys are then null too.
  const auto check = [](const nlohmann::json& checks, const char* key) {
    return checks.is_object() ? checks.value(key, nlohmann::json()) : nlohmann::json();
  };
  return {{"compliance_before", compliance_before},
          {"compliance_after", compliance_after},
          {"compliance_ratio", compliance_ratio},
          {"offset_max", offset_max},
          {"offset_mean", offset_mean},
          {"displacement_max", displacement_max},
          {"slide_max", slide_max},
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
          {"kept_planarised", kept_planarised},
          {"stop", stop},
          {"frame_seconds", seconds_frame},
          {"ceres_seconds", seconds_ceres},
          {"buckling_factor_before", check(checks_before, "buckling_factor")},
          {"buckling_factor_after", check(checks_after, "buckling_factor")},
          {"utilisation_max_before", check(checks_before, "utilisation_max")},
          {"utilisation_max_after", check(checks_after, "utilisation_max")},
          {"span_over_deflection_before", check(checks_before, "span_over_deflection")},
          {"span_over_deflection_after", check(checks_after, "span_over_deflection")}};
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
constexpr double kJointWeight = 1e4;      // joints stay joints (the frame's topology is fixed)
constexpr double kHingeWeight = 1e4;      // × stiffen.weights.edge_length: at weight 1 a member 5 mm short of its
                                          // minimum costs ~0.1 × C₀ at h = 1.25 m (at 1 × it cost 1e-5 and a
                                          // member of the strain grid shrank into a joint)
constexpr double kRestartGain = 1e-3;     // a fresh L-BFGS run that gains less ends the stage
constexpr double kStationary = 1e-9;      // a normal gradient below this (max |∂F/∂z_n|, F ~ 1) is a stationary start
constexpr double kBump = 0.1;             // … from which the run starts at a bump of this × the normal room
constexpr int kLineSearchSteps = 4;       // Wolfe steps per line search: the projection changes along it, and
                                          // zooming longer for the curvature condition rarely paid (h = 3 m, 1.25 m)
// A run that did not move at all is run again once with Ceres' default of Wolfe steps. The Great
// Court at h = 1.25 m × curvature on a 0.5 h reference: the first line search found C/C₀ 0.9974
// at a z-step of 0.011, tried 0.11 for the curvature condition, whose retraction failed, and
// with its four steps spent Ceres reported the start (step 0, "Parameter tolerance reached"):
// the stage ended at C × 1 with a warning.
constexpr int kLongLineSearchSteps = 20;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// F(z) = C(x)/C₀ + fairness change + member hinge + joint hinge, x = f + R q, q = centre +
// radius ∘ sin z per free vertex (BoxVariables). Planarity is not a term: it is the manifold
// (problems/stiffen_manifold.h). The hinge and fairness terms are Ceres residual blocks on
// the world positions, evaluated with their gradient by ceres::Problem::Evaluate; C and ∇C
// by the adjoint (problems/grid_frame.h), on the frame whose joints are the start's.
class Objective final : public ceres::FirstOrderFunction {
 public:
  Objective(const StiffenProblem& P, const std::vector<Restraints>& restraints, const AnalysisOptions& analysis,
            double c0, const GridFrame& frame, PolyMesh* mesh, StiffenReport* report)
      : P_(P), box_(P), restraints_(restraints), analysis_(analysis), c0_(c0), mesh_(mesh), report_(report) {
    positions_.resize(P.held.size());
    ceres::Problem::Options options;
    options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    terms_ = std::make_unique<ceres::Problem>(options);
    for (auto& p : positions_) terms_->AddParameterBlock(p.data(), 3);
    for (size_t v = 0; v < P.held.size(); ++v)
      if (P.held[v]) terms_->SetParameterBlockConstant(positions_[v].data());
    for (size_t t = 0; t < P.triples.size(); ++t) {
      const auto& [a, v, b] = P.triples[t];
      if (P.weights.fairness > 0.0 && !(P.held[a] && P.held[v] && P.held[b]))
        terms_->AddResidualBlock(FairnessChangeResidual::Create(P.second_difference0[t], P.weights.fairness, P.h),
                                 nullptr, Block(a), Block(v), Block(b));
    }
    for (const auto& [i, j, min_length] : P.members)
      if (P.weights.edge_length > 0.0 && !(P.held[i] && P.held[j]))
        terms_->AddResidualBlock(EdgeLengthResidual::Create(min_length, kHingeWeight * P.weights.edge_length, P.h), nullptr,
                                 Block(i), Block(j));
    for (const auto& [i, j, max_length] : P.joint_edges)
      if (!(P.held[i] && P.held[j]))
        terms_->AddResidualBlock(JointLengthResidual::Create(max_length, kJointWeight, P.h), nullptr, Block(i), Block(j));
    for (const int v : box_.free()) evaluate_options_.parameter_blocks.push_back(Block(v));
    for (const auto e : mesh->edges()) {  // the start's joints stay the joints (grid_frame.h)
      const auto he = mesh->halfedge_handle(e, 0);
      joint_edges_.push_back(frame.node_of[mesh->from_vertex_handle(he).idx()] == frame.node_of[mesh->to_vertex_handle(he).idx()]);
    }
  }

  int NumParameters() const override { return box_.size(); }
  const StiffenProblem& problem() const { return P_; }
  const BoxVariables& box() const { return box_; }
  double last_ratio() const { return last_ratio_; }  // C/C₀ at the last evaluation
  int evaluations() const { return report_->evaluations; }

  bool Evaluate(const double* z, double* cost, double* gradient) const override;

 private:
  double* Block(int v) { return positions_[v].data(); }

  const StiffenProblem& P_;
  const BoxVariables box_;
  const std::vector<Restraints>& restraints_;
  const AnalysisOptions& analysis_;
  const double c0_;
  PolyMesh* mesh_;
  StiffenReport* report_;
  mutable std::vector<Vec3> positions_;  // the terms' parameter blocks (world)
  std::unique_ptr<ceres::Problem> terms_;
  ceres::Problem::EvaluateOptions evaluate_options_;
  std::vector<bool> joint_edges_;
  mutable double last_ratio_ = 1.0;
  mutable FrameWorkspace solver_;  // keeps K's pattern and the factor's symbolic analysis across evaluations
};

bool Objective::Evaluate(const double* z, double* cost, double* gradient) const {
  const std::vector<Vec3> x = World(P_, box_.Local(z));
  for (size_t v = 0; v < x.size(); ++v) positions_[v] = x[v];
  double terms = 0.0;
  std::vector<double> terms_gradient;
  if (!terms_->Evaluate(evaluate_options_, &terms, nullptr, gradient ? &terms_gradient : nullptr, nullptr)) return false;
  const auto start = std::chrono::steady_clock::now();
  SetPoints(x, mesh_);
  GridCompliance c;
  const Status status =
      EvaluateGridCompliance(*mesh_, restraints_, analysis_, gradient != nullptr, &c, &solver_, &joint_edges_);
  report_->seconds_frame += Seconds(start);
  ++report_->evaluations;
  if (!status.ok()) return false;  // a mechanism: Ceres' line search shortens the step
  *cost = c.compliance / c0_ + terms;
  last_ratio_ = c.compliance / c0_;
  if (gradient == nullptr) return true;
  for (size_t k = 0; k < box_.free().size(); ++k) {
    const int v = box_.free()[k];
    const Vec3 gx = c.gradient[v] / c0_ + Vec3(terms_gradient[3 * k], terms_gradient[3 * k + 1], terms_gradient[3 * k + 2]);
    for (int d = 0; d < 3; ++d) gradient[3 * k + d] = gx.dot(box_.Derivative(static_cast<int>(k), d, z));
  }
  return true;
}

// ceres::GradientProblem owns its function and manifold; ours outlive the restarts, so each
// run gets these non-owning forwarders.
class BorrowedFunction final : public ceres::FirstOrderFunction {
 public:
  explicit BorrowedFunction(const ceres::FirstOrderFunction& f) : f_(f) {}
  bool Evaluate(const double* z, double* cost, double* gradient) const override { return f_.Evaluate(z, cost, gradient); }
  int NumParameters() const override { return f_.NumParameters(); }

 private:
  const ceres::FirstOrderFunction& f_;
};

class BorrowedManifold final : public ceres::Manifold {
 public:
  explicit BorrowedManifold(const ceres::Manifold& m) : m_(m) {}
  int AmbientSize() const override { return m_.AmbientSize(); }
  int TangentSize() const override { return m_.TangentSize(); }
  bool Plus(const double* x, const double* d, double* y) const override { return m_.Plus(x, d, y); }
  bool PlusJacobian(const double* x, double* j) const override { return m_.PlusJacobian(x, j); }
  bool RightMultiplyByPlusJacobian(const double* x, int rows, const double* a, double* t) const override {
    return m_.RightMultiplyByPlusJacobian(x, rows, a, t);
  }
  bool Minus(const double* y, const double* x, double* d) const override { return m_.Minus(y, x, d); }
  bool MinusJacobian(const double* x, double* j) const override { return m_.MinusJacobian(x, j); }

 private:
  const ceres::Manifold& m_;
};

// Logs every 50th iteration (the stage runs for tens of seconds on fine grids) and ends the
// minimisation when stiffen.stop_window iterations lowered F by less than stiffen.stop_gain of
// it: at the defaults (20, 0.5 %), measured on the Great Court (h = 3 m and 1.25 m), C/C₀ is
// then within 0.5 % of its converged value, and what follows polishes the fairness term for as
// long again.
// One Progress spans every L-BFGS run of the stage (its window carries across restarts: on a
// 112k-triangle Great Court reference every run stopped in its line search after 7 iterations,
// a per-run window of 20 never filled, and the stage spent its 1000 iterations, 47 s). It also
// keeps each run's first and last objective: Ceres' summary of a run that ends in a line-search
// failure reports 1 → −1.
class Progress final : public ceres::IterationCallback {
 public:
  Progress(const Objective& F, const PlanarityManifold& manifold, int window, double gain)
      : F_(F), manifold_(manifold), window_(window, gain) {}
  // Called before each run with the iterations spent so far.
  void StartRun(int offset) {
    offset_ = offset;
    run_first_ = run_last_ = std::numeric_limits<double>::quiet_NaN();
  }
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (VLOG_IS_ON(1) || ((s.iteration + offset_) % 50 == 0 && s.iteration > 0))  // -v: every iteration
      LOG(INFO) << "stiffen: iteration " << s.iteration + offset_ << ", objective " << s.cost << ", C/C₀ "
                << F_.last_ratio() << ", " << manifold_.active() << " planarity constraints active, "
                << F_.evaluations() << " frame solves";
    if (s.iteration == 0) run_first_ = s.cost;
    run_last_ = s.cost;
    if (s.iteration == 0 && !window_.empty()) return ceres::SOLVER_CONTINUE;  // the last run's end again
    if (!window_.AddAndCheckStalled(s.cost)) return ceres::SOLVER_CONTINUE;
    converged_ = true;
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }
  bool converged() const { return converged_; }
  // What the last run gained, relative to its start (0 if it saw no iteration).
  double run_first() const { return run_first_; }
  double run_last() const { return run_last_; }
  double RunGain() const { return run_first_ > run_last_ ? (run_first_ - run_last_) / std::abs(run_first_) : 0.0; }

 private:
  const Objective& F_;
  const PlanarityManifold& manifold_;
  int offset_ = 0;
  double run_first_ = 0.0, run_last_ = 0.0;
  CostWindow window_;
  bool converged_ = false;
};

// L-BFGS (Ceres' GradientProblemSolver) on the planarity manifold, restarted with a fresh
// memory when its line search stops short (the projection changes along the way, and the
// stored pairs can stop describing it), until Progress says converged, a run gains less than
// kRestartGain, or stiffen.max_iterations are spent.
// run_ends: the state at the end of every run, first to last (the caller falls back on an
// earlier one if the last cannot be made planar again).
Status Minimise(const Objective& F, double allowed, const StiffenOptions& options, std::vector<Vec3>* q,
                std::vector<std::vector<Vec3>>* run_ends, StiffenReport* report) {
  std::vector<double> z = F.box().Parameters(*q);
  PlanarityManifold manifold(F.problem(), F.box(), allowed);
  if (!manifold.Retract(z.data()))
    LOG(INFO) << "stiffen: the start could not be brought within δ " << allowed << " on every sub-quad; "
              << manifold.AdmitStart(z.data()) << " sub-quads keep their start's δ as their bound";
  Progress progress(F, manifold, options.stop_window, options.stop_gain);
  int line_search_steps = kLineSearchSteps;
  for (int budget = options.max_iterations, run = 1; budget > 0; ++run) {
    ceres::GradientProblem problem(new BorrowedFunction(F), new BorrowedManifold(manifold));
    ceres::GradientProblemSolver::Options solver_options;
    solver_options.max_num_iterations = budget;
    solver_options.function_tolerance = 1e-6;
    solver_options.use_approximate_eigenvalue_bfgs_scaling = true;  // 13 % fewer evaluations at h = 1.25 m
    solver_options.max_num_line_search_step_size_iterations = line_search_steps;
    solver_options.logging_type = ceres::SILENT;
    // Keeps every accepted step in z: Ceres writes the solution back only for a usable
    // summary, and a run that ends in a line-search failure (FAILURE) would otherwise restart
    // from where it began (measured: 142 identical 7-iteration runs on a 112k-triangle Great
    // Court reference, 47 s, keeping only the last run's 6 iterations).
    solver_options.update_state_every_iteration = true;
    InterruptCallback interrupt;
    progress.StartRun(report->iterations);
    solver_options.callbacks = {&interrupt, &progress};
    ceres::GradientProblemSolver::Summary summary;
    const auto start = std::chrono::steady_clock::now();
    ceres::Solve(solver_options, problem, z.data(), &summary);
    report->seconds_ceres += Seconds(start);
    PQ_RETURN_IF_ERROR(CheckInterrupt());
    const int iterations = std::max(1, static_cast<int>(summary.iterations.size()) - 1);
    report->iterations += iterations, budget -= iterations;
    run_ends->push_back(F.box().Local(z.data()));
    report->stop = progress.converged() ? "converged" : summary.message;
    LOG(INFO) << "stiffen: L-BFGS run " << run << ": " << iterations << " iterations, objective "
              << progress.run_first() << " → " << progress.run_last() << " (" << summary.message << ")";
    const bool stuck = iterations <= 1 && !(progress.RunGain() > 0.0);
    if (stuck && line_search_steps == kLineSearchSteps && !progress.converged()) {
      LOG(INFO) << "stiffen: run " << run << " did not move; again with " << kLongLineSearchSteps << " line-search steps";
      line_search_steps = kLongLineSearchSteps;
      continue;
    }
    line_search_steps = kLineSearchSteps;
    if (progress.converged() || (summary.termination_type == ceres::FAILURE && iterations <= 1)) break;
    if (progress.RunGain() < kRestartGain) break;
  }
  *q = F.box().Local(z.data());
  return Status::Ok();
}

// Never hands on a shell whose panels are less planar than the target (or than the planarised
// shell, x0): the last run's end made planar again (RestorePlanarity), else the latest earlier
// run's end that can be (on a 112k-triangle Great Court reference the last run ended at δ 0.0022
// that no projection inside the boxes brings below 0.001, while the first run's end, C/C₀ 0.73,
// could), else the start, marked kept_planarised (StiffenMesh then hands on x0 itself, bit for
// bit). Comparing with the start instead of x0 once let a start whose vertices had been pulled
// inside a tight tolerance hand on bent panels (δ 0.0016 at 5 mm on the Great Court).
Status KeepPlanar(const StiffenProblem& P, double target_delta, const std::vector<Vec3>& x0,
                  const std::vector<Vec3>& q_start, const std::vector<std::vector<Vec3>>& run_ends,
                  std::vector<Vec3>* q, StiffenReport* report) {
  const double allowed = std::max(target_delta, MaxPlanarity(P, x0));
  for (auto end = run_ends.rbegin(); end != run_ends.rend(); ++end) {
    std::vector<Vec3> candidate = *end;
    PQ_RETURN_IF_ERROR(RestorePlanarity(P, target_delta, &candidate));
    const double delta = MaxPlanarity(P, World(P, candidate));
    if (delta <= allowed) {
      if (end != run_ends.rbegin())
        LOG(WARNING) << "stiffen: the last L-BFGS run's shell could not be brought within planarize.target_delta "
                     << target_delta << "; keeping the end of run " << run_ends.rend() - end << " (δ max " << delta
                     << ")";
      *q = std::move(candidate);
      return Status::Ok();
    }
  }
  LOG(WARNING) << "stiffen: no reshaped shell could be brought within planarize.target_delta " << target_delta
               << " inside the tolerance boxes; keeping the planarised shell (allow more room: stiffen.slide, "
               << "stiffen.tolerance)";
  *q = q_start;
  report->kept_planarised = true;
  return Status::Ok();
}

void Measure(const StiffenProblem& P, const ClosestPointQuery& query, const std::vector<Vec3>& x0,
             const GridCompliance& first, const GridCompliance& last, const std::vector<Vec3>& x, PolyMesh* mesh,
             StiffenReport* r) {
  r->compliance_before = first.compliance;
  r->compliance_after = last.compliance;
  r->compliance_ratio = r->compliance_after / r->compliance_before;
  r->steel_mass_change = last.frame.steel_mass / first.frame.steel_mass - 1.0;
  r->planarity_max = MaxPlanarity(P, x);
  r->normal_offset.assign(x.size(), 0.0);
  r->closeness_max = r->offset_max = r->offset_mean = r->displacement_max = r->slide_max = 0.0;
  for (size_t v = 0; v < x.size(); ++v) {
    r->closeness_max = std::max(r->closeness_max, query.OnSurface(x[v]).distance);
    const Vec3 normal = P.held[v] ? query.OnSurface(x0[v]).normal : Vec3(P.frames[v].rotation.col(2));
    r->normal_offset[v] = (x[v] - x0[v]).dot(normal);
    r->offset_max = std::max(r->offset_max, std::abs(r->normal_offset[v]));
    r->offset_mean += std::abs(r->normal_offset[v]) / x.size();
    r->displacement_max = std::max(r->displacement_max, (x[v] - x0[v]).norm());
    r->slide_max = std::max(r->slide_max, (x[v] - x0[v] - r->normal_offset[v] * normal).norm());
  }
  r->min_member_length = std::numeric_limits<double>::infinity();
  for (const auto& [i, j, min_length] : P.members) r->min_member_length = std::min(r->min_member_length, (x[i] - x[j]).norm());
  SetPoints(x, mesh);
  const std::vector<double> kinks = KinkAngles(*mesh);
  r->kink_mean_deg_after = r->kink_max_deg_after = 0.0;
  for (const double k : kinks) r->kink_mean_deg_after += k / kinks.size(), r->kink_max_deg_after = std::max(r->kink_max_deg_after, k);
}

// True if the objective's gradient along the reference normals vanishes at q: a flat plate
// under gravity is a saddle of its compliance (arching up or sagging down both stiffen it),
// where L-BFGS, seeing only the small in-plane gradient, never leaves the plane.
bool Stationary(const Objective& F, const std::vector<Vec3>& q) {
  const std::vector<double> z = F.box().Parameters(q);
  std::vector<double> gradient(z.size());
  double cost = 0.0;
  if (z.empty() || !F.Evaluate(z.data(), &cost, gradient.data())) return false;
  double normal = 0.0, tangential = 0.0;
  for (size_t i = 0; i < gradient.size(); ++i)
    (i % 3 == 2 ? normal : tangential) = std::max(i % 3 == 2 ? normal : tangential, std::abs(gradient[i]));
  return normal <= kStationary * std::max(tangential, 1.0);
}

// q with every free vertex lifted along its reference normal by kBump × its normal room ×
// (its edge-hop distance from the held vertices / the largest such distance): a dome-shaped
// start that breaks the symmetry of a stationary planarised shell.
std::vector<Vec3> Bumped(const StiffenProblem& P, const PolyMesh& mesh, std::vector<Vec3> q) {
  std::vector<int> hops(P.held.size(), -1);
  std::deque<int> queue;
  for (size_t v = 0; v < P.held.size(); ++v)
    if (P.held[v]) hops[v] = 0, queue.push_back(static_cast<int>(v));
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop_front();
    for (const auto w : mesh.vv_range(VertexHandle(v)))
      if (hops[w.idx()] < 0) hops[w.idx()] = hops[v] + 1, queue.push_back(w.idx());
  }
  const int deepest = std::max(1, *std::max_element(hops.begin(), hops.end()));
  for (size_t v = 0; v < q.size(); ++v)
    if (!P.held[v] && hops[v] > 0) q[v][2] = std::min(P.upper[v][2], q[v][2] + kBump * P.upper[v][2] * hops[v] / deepest);
  return q;
}

}  // namespace

Status StiffenMesh(const SurfaceModel& reference, const std::vector<Restraints>& restraints,
                   const AnalysisOptions& analysis, const StiffenOptions& options, double target_delta, double h,
                   ExtractedMesh* mesh, StiffenReport* report, BucklingMemo* memo) {
  const std::vector<double> kinks = KinkAngles(mesh->mesh);
  for (const double k : kinks)
    report->kink_mean_deg_before += k / kinks.size(), report->kink_max_deg_before = std::max(report->kink_max_deg_before, k);
  std::vector<Vec3> x0(mesh->mesh.n_vertices());
  for (const auto v : mesh->mesh.vertices()) x0[v.idx()] = ToEigen(mesh->mesh.point(v));
  const ClosestPointQuery& query = reference.closest_points();
  GridFrame frame;
  BuildGridFrame(mesh->mesh, restraints, analysis, &frame);
  StiffenProblem P;
  std::vector<Vec3> q;
  SetUpStiffenProblem(query, *mesh, frame, analysis.section, options, h, &P, &q);
  for (const bool held : P.held) report->held_vertices += held;
  GridCompliance first;
  SetPoints(World(P, q), &mesh->mesh);
  PQ_RETURN_IF_ERROR(EvaluateGridCompliance(mesh->mesh, restraints, analysis, false, &first).WithContext("stiffen"));
  if (report->held_vertices == static_cast<int>(x0.size())) report->stop = "no room: every vertex is held";
  if (options.tolerance > 0.0 && options.max_iterations > 0 && report->held_vertices < static_cast<int>(x0.size())) {
    const Objective F(P, restraints, analysis, first.compliance, frame, &mesh->mesh, report);
    const std::vector<Vec3> q_start = q;
    if (Stationary(F, q)) {
      LOG(INFO) << "stiffen: the planarised shell is a stationary point of the compliance (flat, or symmetric about "
                   "its reference); starting from a bump of "
                << kBump << " × the tolerance along the reference normal";
      q = Bumped(P, mesh->mesh, q);
    }
    std::vector<std::vector<Vec3>> run_ends;
    PQ_RETURN_IF_ERROR(Minimise(F, kPlanarityMargin * target_delta, options, &q, &run_ends, report));
    PQ_RETURN_IF_ERROR(KeepPlanar(P, target_delta, x0, q_start, run_ends, &q, report));
  }
  std::vector<Vec3> x = World(P, q);
  GridCompliance last;
  SetPoints(x, &mesh->mesh);
  PQ_RETURN_IF_ERROR(EvaluateGridCompliance(mesh->mesh, restraints, analysis, false, &last).WithContext("stiffen"));
  // Nor one that is softer than where it started (the start can differ from the planarised
  // shell, see KeepPlanar): then the planarised shell itself, before = after.
  if (report->kept_planarised || last.compliance > first.compliance) {
    if (!report->kept_planarised)
      LOG(WARNING) << "stiffen: the reshaped shell is softer than the planarised one (" << last.compliance << " J vs "
                   << first.compliance << " J); keeping the planarised shell";
    report->kept_planarised = true;
    x = x0;
    SetPoints(x, &mesh->mesh);
    PQ_RETURN_IF_ERROR(EvaluateGridCompliance(mesh->mesh, restraints, analysis, false, &last).WithContext("stiffen"));
    first = last;
  }
  if (report->iterations > 0) {  // what the reshaping did to buckling, utilisation and deflection
    StructuralChecks before, after;
    PQ_RETURN_IF_ERROR(RunStructuralChecks(first.frame, first.result, analysis, &before, false, memo).WithContext("stiffen"));
    PQ_RETURN_IF_ERROR(RunStructuralChecks(last.frame, last.result, analysis, &after, false, memo).WithContext("stiffen"));
    report->checks_before = before.ToJson(first.frame), report->checks_after = after.ToJson(last.frame);
    LOG(INFO) << "stiffen: buckling factor " << report->checks_before["buckling_factor"] << " → "
              << report->checks_after["buckling_factor"] << ", utilisation max " << report->checks_before["utilisation_max"]
              << " → " << report->checks_after["utilisation_max"] << ", span / deflection "
              << report->checks_before["span_over_deflection"] << " → " << report->checks_after["span_over_deflection"];
  }
  if (last.frame.joints != first.frame.joints)  // the hinges are penalties: say so if one gave way
    LOG(WARNING) << "stiffen: the frame has " << last.frame.joints << " joints after, " << first.frame.joints
                 << " before (a member became shorter than the section depth, or a joint longer)";
  Measure(P, query, x0, first, last, x, &mesh->mesh, report);
  return Status::Ok();
}

}  // namespace pqlayout
