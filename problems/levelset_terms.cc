// Ceres plumbing of the level-set solves: one solve with its log, charts carrying the seam transitions, the smoothness and spacing terms.
#include "problems/levelset_internal.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/format_number.h"
#include "problems/residuals/smoothness_residual.h"
#include "problems/residuals/spacing_residual.h"
#include "solver/affine_mapped_cost.h"
#include "solver/ceres_options.h"
#include "solver/cost_window.h"

namespace pqlayout {
namespace levelset_internal {

// ---- Ceres ---------------------------------------------------------------------------

// A solve's log name: "(alongside) phi" on a second layout's thread (AlongsideSolve).
std::string LogName(const std::string& name) {
  return AlongsideSolve::OnThisThread() ? "(alongside) " + name : name;
}

class ProgressLog : public ceres::IterationCallback {
 public:
  explicit ProgressLog(std::string name) : name_(LogName(name)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    VLOG(1) << name_ << " iteration " << it.iteration << ": cost " << it.cost;
    if (it.iteration > 0 && it.iteration % 25 == 0)
      LOG(INFO) << "levelset: " << name_ << " iteration " << it.iteration << ", cost " << it.cost;
    return ceres::SOLVER_CONTINUE;
  }

 private:
  std::string name_;
};

// Ends a solve that crawls: from iteration kStallFrom on, once the cost fell by less than
// kStallGain of it over the last kStallWindow − 1 = 24 iterations (solver/cost_window.h).
// Levenberg–Marquardt on these problems reaches its basin in tens of iterations; on most roofs
// Ceres' function tolerance then ends the joint solve (all corpus runs within 96 iterations),
// but on some it crawls: the wavy roof's (curvature) went 860 → 842 → 839 → … → 829 at
// iterations 25, 50, 75, … 300, 34 s of its 47 s for the last 1.2 %. Why not from the start:
// the layout after the crossing rounds is chaotic in the joint solve's end point on roofs
// whose crossing target cannot be met (index +1 crowns) — stopping wavy × strain at 46
// iterations instead of Ceres' 69, 0.01 % above in cost, turned its min crossing from 18.8°
// into 4.3° — so solves that converge by themselves keep their end point (outputs
// byte-identical there and on the Great Court) and only a crawl past kStallFrom is cut short.
constexpr int kStallFrom = 100;
constexpr int kStallWindow = 25;
constexpr double kStallGain = 0.005;

class StallStop : public ceres::IterationCallback {
 public:
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    fired_ = window_.AddAndCheckStalled(it.cost) && it.iteration >= kStallFrom;
    return fired_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
  }
  bool fired() const { return fired_; }

 private:
  CostWindow window_{kStallWindow, kStallGain};
  bool fired_ = false;
};

nlohmann::json SummaryJson(const ceres::Solver::Summary& s) {
  return {{"iterations", s.iterations.size() > 0 ? s.iterations.size() - 1 : 0},
          {"initial_cost", s.initial_cost},
          {"final_cost", s.final_cost},
          {"termination", ceres::TerminationTypeToString(s.termination_type)},
          {"seconds", s.total_time_in_seconds},
          {"residual_blocks", s.num_residual_blocks},
          {"linear_solver", ceres::LinearSolverTypeToString(s.linear_solver_type_used)},
          {"message", s.message}};
}

// levelset.linear_solver = cg (cg_steps): each step by conjugate gradients on the normal
// equations, preconditioned by the Cholesky factor (Eigen's, as every solve's:
// solver/ceres_options.h) of the normal equations without the smoothness terms (Ceres' SUBSET
// preconditioner). The smoothness term is the only one reading an edge's two opposite
// vertices; with it the factor of the Great Court's joint solve (12.9k unknowns) took 105 ms
// an iteration, without it ~30 ms, and its weight (0.01 against 5–100) leaves conjugate
// gradients little to do. Each step's iterations go on until the i-th improves the quadratic
// model by less than kForcing / i of it (Ceres' eta): at Ceres' default 0.1 the inexact steps
// made a different optimiser (the wavy roof × curvature lost its poles and aligned to 37.8°
// instead of 2.8°). Not the default: a different draw everywhere, faster (corpus level sets
// × 0.62–0.83) and as stiff over seven Great Court meshes, but on the corpus 13 of 22 runs met
// every target instead of 15 and the 309k Great Court's strain layout crossed at 26.5°
// (benchmarks/RESULTS.md, "The level sets' steps by conjugate gradients"). Without any
// smoothness block the factor is exact and the plain sparse Cholesky is used.
constexpr double kForcing = 1e-3;

Status Solve(const std::string& name, int max_iterations, TermProblem* terms, nlohmann::json* summary,
             bool stop_on_stall) {
  ceres::Problem* problem = &terms->problem;
  ceres::Solver::Options options = SparseCholeskyOptions(max_iterations);
  if (terms->cg_steps && !terms->smoothness.empty()) {
    std::vector<ceres::ResidualBlockId> blocks;
    problem->GetResidualBlocks(&blocks);
    for (const ceres::ResidualBlockId id : blocks)
      if (terms->smoothness.count(id) == 0) options.residual_blocks_for_subset_preconditioner.insert(id);
    if (!options.residual_blocks_for_subset_preconditioner.empty()) {
      options.linear_solver_type = ceres::CGNR;
      options.preconditioner_type = ceres::SUBSET;
      options.eta = kForcing;
    }
  }
  ProgressLog progress(name);
  StallStop stall;
  options.callbacks.push_back(&progress);
  if (stop_on_stall) options.callbacks.push_back(&stall);
  ceres::Solver::Summary result;
  ceres::Solve(options, problem, &result);
  *summary = SummaryJson(result);
  if (stall.fired()) {  // say why in report.json instead of Ceres' "User callback returned …"
    (*summary)["termination"] = "STALLED";
    std::string message = "stalled: the last " + std::to_string(kStallWindow - 1) + " iterations lowered the cost by less than ";
    AppendNumber(&message, 100.0 * kStallGain, 6);
    (*summary)["message"] = message + " %";
  }
  VLOG(1) << "levelset: " << LogName(name) << ":\n" << result.FullReport();
  if (!result.IsSolutionUsable()) return Status::Internal("levelset: Ceres failed on " + name + ": " + result.message);
  LOG(INFO) << "levelset: " << LogName(name) << ": " << result.iterations.size() - 1 << " iterations, cost "
            << result.initial_cost << " → " << result.final_cost << " ("
            << (stall.fired() ? "STALLED" : ceres::TerminationTypeToString(result.termination_type)) << ", "
            << result.total_time_in_seconds << " s)";
  return Status::Ok();
}

ceres::LossFunction* TermProblem::Weight(double w) {
  auto [it, added] = weights_.try_emplace(w, nullptr);
  if (added) it->second = new ceres::ScaledLoss(nullptr, w, ceres::TAKE_OWNERSHIP);
  return it->second;
}

// `live`: vertex mask; a term is added if it touches a live vertex (nullptr: all).
bool Live(const std::vector<char>* live, std::initializer_list<int> ids) {
  if (live == nullptr) return true;
  for (const int v : ids)
    if ((*live)[v]) return true;
  return false;
}


// Adds `cost` over the given scalars (chart, vertex), through their maps.
ceres::ResidualBlockId AddMapped(ceres::Problem* problem, ceres::CostFunction* cost, ceres::LossFunction* loss,
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
  return problem->AddResidualBlock(cost, loss, blocks);
}

void AddSmoothness(const std::vector<InteriorEdge>& edges, double h, double weight, const Chart& u, TermProblem* terms, const std::vector<char>* live) {
  if (weight <= 0.0) return;
  for (const auto& e : edges) {
    if (!Live(live, {e.i, e.j, e.k, e.l})) continue;
    terms->AddSmoothnessBlock(AddMapped(&terms->problem, SmoothnessResidual::Create(e.Gf, e.Gg, e.area, e.distance, h),
                                       terms->Weight(weight), {{&u, u.At(e.i)}, {&u, u.At(e.j)}, {&u, u.At(e.k)}, {&u, u.At(e.l)}}));
  }
}

// A face with target ρ asks for the local spacing h / ρ, weighted ρ², i.e. r_f = √(wA_f) (h|∇u_f| − ρ).
void AddSpacing(const SurfaceModel& s, const LevelSetGeometry& geo, double h, double weight, const Chart& u,
                const std::vector<double>& target, TermProblem* terms, const std::vector<char>* live) {
  if (weight <= 0.0) return;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    if (!Live(live, {ids[0], ids[1], ids[2]})) continue;
    const double rho = target.empty() ? 1.0 : target[f];
    AddMapped(&terms->problem, SpacingResidual::Create(geo.G[f], s.face_area(f), h / rho), terms->Weight(weight * rho * rho),
              {{&u, u.At(ids[0])}, {&u, u.At(ids[1])}, {&u, u.At(ids[2])}});
  }
}

std::vector<double> ConeSpacingTargets(const LevelSetGeometry& geo, const std::vector<Eigen::Vector3d>& tips,
                                       double radius, double h) {
  constexpr double kFloor = 0.05;  // never reached on a mesh (a centroid is ≳ 0.1 edge from a vertex): no 0 target
  if (tips.empty() || !(radius > 0.0)) return {};
  std::vector<double> target(geo.centroid.size());
  for (size_t f = 0; f < target.size(); ++f) {
    double d = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& t : tips) d = std::min(d, (geo.centroid[f] - t).norm());
    target[f] = std::max(kFloor, std::min(1.0, std::pow(d / (radius * h), 0.5)));
  }
  return target;
}

}  // namespace levelset_internal
}  // namespace pqlayout
