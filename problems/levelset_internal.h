// Shared inside the level-set problem (problems/levelset_*.cc and stage_levelset.cc), not its
// interface (that is problems/levelset.h): the per-face geometry, the initial guess, the Ceres
// plumbing, the metrics and the solves, one file each.
#pragma once

#include <ceres/ceres.h>

#include <array>
#include <atomic>
#include <exception>
#include <functional>
#include <initializer_list>
#include <string>
#include <system_error>
#include <thread>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <nlohmann/json.hpp>

#include "base/interrupt.h"
#include "problems/guidance.h"
#include "problems/levelset.h"

namespace pqlayout::levelset_internal {

constexpr double kDegrees = 180.0 / M_PI;

// Per-face data shared by every term, computed once.
struct LevelSetGeometry {
  std::vector<Eigen::Matrix3d> G;      // P1 basis gradients, columns in face_vertices order
  std::vector<Eigen::Matrix3d> S;      // shape operators
  std::vector<Eigen::Vector3d> centroid;
  double flat_curvature = 0.0;         // μ: below this curvature, conjugacy becomes orthogonality
};

// An interior edge (i, j) between face f (third vertex k) and face g (third vertex l).
struct InteriorEdge {
  int i, j, k, l;
  int f, g;
  Eigen::Matrix3d Gf, Gg;  // basis gradients in the order (i, j, k) and (i, j, l)
  double area, distance;
};

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

// A seam edge as the seam smoothness term sees it (cut vertex ids): i, j, k in the minus face
// f, i, j, l in the plus face g (i, j the same original vertices).
struct SeamEdgeTerm {
  int path;
  int i_minus, j_minus, k, i_plus, j_plus, l;
  Eigen::Matrix3d Gf, Gg;
  double area, distance;
};

// levelset_geometry.cc
LevelSetGeometry Precompute(const SurfaceModel& surface);
Eigen::Vector3d Gradient(const LevelSetGeometry& geo, const SurfaceModel& s, int f, const std::vector<double>& u);
Eigen::Matrix3d OrderedBasis(const LevelSetGeometry& geo, const SurfaceModel& s, int f, const std::array<int, 3>& order);
std::vector<InteriorEdge> InteriorEdges(const SurfaceModel& s, const LevelSetGeometry& geo);
// The edges the smoothness term acts on: those with a face whose guidance weight is ≤
// max_weight (levelset.smoothness_max_guidance; ≥ 1: every edge).
std::vector<InteriorEdge> SmoothedEdges(const std::vector<InteriorEdge>& edges, const GuidanceField& g, double max_weight);
std::vector<SeamEdgeTerm> SeamEdgeTerms(const SurfaceModel& s, const LevelSetGeometry& geo, const SeamCut& cut);

// levelset_initial.cc
std::vector<Eigen::Vector3d> OrientedCrossField(const SurfaceModel& s, const GuidanceField& g);
Status PoissonFit(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<Eigen::Vector3d>& target, const std::vector<double>& omega, std::vector<double>* u, LevelSetSeams* seams = nullptr, int family = 0, bool free_offsets = false, double h = 1.0, Eigen::MatrixXd* offset_block = nullptr);
void RoundOffsets(const LevelSetSeams& seams, std::vector<double>* offsets, const Eigen::MatrixXd* block = nullptr);
Status SeamedPoissonFit(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<Eigen::Vector3d>& target, const std::vector<double>& omega, double h, int family, LevelSetSeams* seams, std::vector<double>* u);
std::vector<int> SeamSigns(const SeamCut& cut, const std::vector<Eigen::Vector3d>& oriented);
void ProjectTransitions(const LevelSetSeams& seams, const std::vector<double>& offsets, std::vector<double>* u);
void AddFaceForm(const Eigen::Vector3d& a, const std::array<int, 3>& ids, double scale, std::vector<Eigen::Triplet<double>>* t);
Eigen::SparseMatrix<double> AlignmentSmoothnessForm(const SurfaceModel& s, const LevelSetGeometry& geo, const GuidanceField& g, const std::vector<InteriorEdge>& edges, double h, const LevelsetWeights& w);
Status SmallestEigenvector(const SurfaceModel& s, const LevelSetGeometry& geo, const GuidanceField& g, const std::vector<InteriorEdge>& edges, double h, const LevelsetWeights& w, std::vector<double>* phi);
std::vector<Eigen::Vector3d> ConjugateTargets(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<double>& phi, double h, double min_angle);
Status InitialGuess(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<InteriorEdge>& edges, const GuidanceField& g, const LevelsetOptions& options, double h, LevelSetSeams* seams, LevelSetSolution* solution);

// levelset_terms.cc
// A level-set solve's Ceres problem and which of its residual blocks are smoothness terms
// (interior and seam edges): the only terms that couple a vertex to the opposite vertices of
// its edges, and so most of the fill of the normal equations; with cg_steps
// (levelset.linear_solver = cg) Solve's preconditioner leaves them out.
// The step solver is fixed at construction, so no solve can forget it; the smoothness blocks
// are recorded only when cg_steps reads them.
// The terms' weights are ScaledLoss objects, one per distinct weight shared by every block
// that has it (Weight): a problem holds ~90k blocks and a handful of weights. The problem owns
// them (Ceres counts the blocks that share one and deletes it with the last).
struct TermProblem {
  explicit TermProblem(bool cg) : cg_steps(cg) {}
  void AddSmoothnessBlock(ceres::ResidualBlockId id) {
    if (cg_steps) smoothness.insert(id);
  }
  ceres::LossFunction* Weight(double w);
  ceres::Problem problem;
  std::unordered_set<ceres::ResidualBlockId> smoothness;  // empty unless cg_steps
  const bool cg_steps;

 private:
  std::unordered_map<double, ceres::LossFunction*> weights_;  // owned by problem
};
// A solve's log name: "(alongside) phi" on a second layout's thread (AlongsideSolve).
std::string LogName(const std::string& name);
// One Ceres solve of at most max_iterations, logged under name; stop_on_stall: also end once
// past iteration 100 the cost fell by less than 0.5 % over the last 24 (levelset_terms.cc, StallStop).
Status Solve(const std::string& name, int max_iterations, TermProblem* terms, nlohmann::json* summary,
             bool stop_on_stall = false);
bool Live(const std::vector<char>* live, std::initializer_list<int> ids);
ceres::ResidualBlockId AddMapped(ceres::Problem* problem, ceres::CostFunction* cost, ceres::LossFunction* loss,
                                 std::initializer_list<std::pair<const Chart*, Scalar>> args);
void AddSmoothness(const std::vector<InteriorEdge>& edges, double h, double weight, const Chart& u, TermProblem* terms, const std::vector<char>* live = nullptr);
// The spacing term; target: ρ_f per face (ConeSpacingTargets), empty for 1 everywhere.
void AddSpacing(const SurfaceModel& s, const LevelSetGeometry& geo, double h, double weight, const Chart& u,
                const std::vector<double>& target, TermProblem* terms, const std::vector<char>* live = nullptr);
// What the spacing term asks of h|∇u| on each face (levelset.tip_cone_radius = R): round a branch
// point u ~ Re z^{3/2}, so |∇u| ~ d^½ at distance d, and ρ_f = min(1, (d_f / (R h))^½) with d_f
// from the face's centroid to the nearest tip; empty (1 everywhere) without tips or with R = 0.
std::vector<double> ConeSpacingTargets(const LevelSetGeometry& geo, const std::vector<Eigen::Vector3d>& tips,
                                       double radius, double h);

// levelset_metrics.cc
LevelSetMetrics Measure(const SurfaceModel& s, const LevelSetGeometry& geo, const GuidanceField& g, const std::vector<double>& phi, const std::vector<double>& psi, double min_angle_deg);

// The rest of a layout's solve, to be run at most once, before *solution is moved or read
// for φ, ψ: the crossing rounds, the final metrics and whatever the caller's layers do after.
using Finish = std::function<Status()>;

// levelset.alongside: how many second layouts that may be needed — the poles' (SolveLevelSets)
// and the cone's retry with its rounds (SolveOnMesh) — and the rounds' floor way (Rounds) may be
// solved at once on threads of their own beside the first, in the whole process: "false" none,
// "true" no limit, "auto" the hardware threads less one (one on a 2-core machine, so that every
// solve has a core), "1" one. Each solve is
// single-threaded on its own data, so the outputs are the same either way. One that turns out
// not to be needed is cancelled as soon as that is known; what it then cost is the first
// layout's time while both ran (on the 2-core machine the example's level sets 1.12× as long,
// its cone's retry not needed), against ~0.7× where it is needed: over the corpus the level
// sets took 0.85× as long (benchmarks/RESULTS.md, "The second layouts alongside the first,
// cancelled when not needed").
int AlongsideBudget(const LevelsetOptions& options);
// One solve on a second thread (levelset.alongside), joined however the scope is left (a
// std::thread destroyed joinable would end the process); an exception thrown in it
// (std::bad_alloc) becomes its Status instead. Left without Join (the first layout failed,
// or the second is not needed), it is cancelled first: its Ceres solves end within one
// iteration (ThreadCancelled) instead of running to their end.
class AlongsideSolve {
 public:
  static constexpr int kNoLimit = 1 << 30;
  // On a thread started by Start: its solves' log lines say so ("levelset: (alongside) phi: …"),
  // since they interleave with the first layout's, whose names they share where the report's do.
  static bool OnThisThread() { return on_this_thread_; }
  // Solves now running alongside, in the whole process.
  static int Running() { return running_.load(); }
  AlongsideSolve() = default;
  AlongsideSolve(const AlongsideSolve&) = delete;
  AlongsideSolve& operator=(const AlongsideSolve&) = delete;
  ~AlongsideSolve() {
    cancel_ = true;
    if (thread_.joinable()) thread_.join();
  }
  // Starts `solve` on a thread of its own unless `budget` solves already run alongside
  // (AlongsideBudget); whether it started. At most once per object.
  bool Start(std::function<Status()> solve, int budget = kNoLimit) {
    int running = running_.load();
    do {
      if (running >= budget) return false;
    } while (!running_.compare_exchange_weak(running, running + 1));
    try {
      thread_ = std::thread([this, solve = std::move(solve)] {
        on_this_thread_ = true;
        SetThreadCancelFlag(&cancel_);
        try {
          status_ = solve();
        } catch (const std::exception& e) {
          status_ = Status::Internal(std::string("levelset: a solve alongside failed: ") + e.what());
        }
        SetThreadCancelFlag(nullptr);
        running_.fetch_sub(1);  // its core is free for another
      });
    } catch (const std::system_error&) {  // no thread to be had: nothing started, solved later if needed
      running_.fetch_sub(1);
      return false;
    }
    return true;
  }
  bool started() const { return thread_.joinable(); }
  // Its Status once it has ended (Ok if never started).
  Status Join() {
    if (thread_.joinable()) thread_.join();
    return status_;
  }

 private:
  static inline thread_local bool on_this_thread_ = false;
  static inline std::atomic<int> running_{0};
  std::atomic<bool> cancel_{false};
  std::thread thread_;
  Status status_ = Status::Ok();
};

// levelset_problem.cc
// finish: null, the whole solve; else it stops after the joint solve with solution->metrics
// measured there and leaves the rounds in *finish (SolveLevelSets compares layouts there).
Status SolveOnMesh(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h, LevelSetSeams* seams, LevelSetSolution* solution, Finish* finish = nullptr);

// levelset_solve.cc
GuidanceField TransferGuidance(const SurfaceModel& reference, const GuidanceField& g, const SurfaceModel& working);
std::vector<int> SeamTips(const SurfaceModel& s, const GuidanceField& g, double h, int* cancelled, std::vector<Eigen::Vector3d>* crowns);
Status SolveWithSeams(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h, LevelSetSolution* solution, Finish* finish = nullptr);

// levelset_poles.cc
std::vector<LevelSetCap> FindCaps(const SurfaceModel& s, const GuidanceField& g, double h);
Status CutCaps(const SurfaceModel& s, const GuidanceField& g, std::vector<LevelSetCap>* caps, std::shared_ptr<const SurfaceModel>* holed, GuidanceField* holed_guidance);
// A whole layout's solve into *out; with a Finish it stops after the joint solve (SolveOnMesh).
using LayoutSolve = std::function<Status(LevelSetSolution* out, Finish* finish)>;
// The layout without poles, or with poles at the crowns (caps) where it misaligns or folds over
// and they align clearly better; alongside (levelset.alongside): the poles' layout solved on a
// second thread from the start.
Status ChoosePoles(std::vector<LevelSetCap> caps, const LayoutSolve& plain, const LayoutSolve& poles, int alongside_budget,
                   LevelSetSolution* solution);

}  // namespace pqlayout::levelset_internal
