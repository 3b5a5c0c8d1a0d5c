// The level-set problem on one mesh (paper §3.1): the terms of φ and ψ on their charts (seam
// transitions included), and the solves: φ alone and ψ with φ held (levelset.separate_solves
// only), both together, then the crossing rounds (with the floor rounds where they fail).
// LevelSetProblem owns what the solves share; the order in which the residual blocks are
// added is the order of the paper's terms and must not change (Ceres' ordering, and with it
// the last bits of every solve, follow it).
#include "problems/levelset_problem.h"

#include <glog/logging.h>

#include <functional>
#include <memory>
#include <utility>

#include "problems/residuals/alignment_residual.h"
#include "problems/residuals/conjugacy_residual.h"
#include "problems/residuals/crossing_barrier_residual.h"
#include "problems/residuals/smoothness_residual.h"
#include "problems/residuals/transversality_residual.h"

namespace pqlayout {
namespace levelset_internal {

std::vector<int> FixedTips(const LevelSetSeams& seams) {
  std::vector<int> tips;
  for (const auto& pair : seams.cut->copy_pairs())
    if (pair.minus == pair.plus && seams.sign[pair.path] < 0) tips.push_back(pair.minus);
  return tips;
}

LevelSetProblem::LevelSetProblem(const SurfaceModel& s, const LevelSetGeometry& geo,
                                 const std::vector<InteriorEdge>& edges, const GuidanceField& g,
                                 const LevelsetOptions& options, double h, LevelSetSeams* seams,
                                 std::vector<SeamEdgeTerm> seam_terms, LevelSetSolution* solution)
    : s_(s), geo_(geo), edges_(SmoothedEdges(edges, g, options.smoothness_max_guidance)), g_(g), options_(options), w_(options.weights), h_(h),
      min_angle_(options.min_angle / kDegrees), seams_(seams), seam_terms_(std::move(seam_terms)),
      solution_(solution), phi_(solution->phi), psi_(solution->psi), phi_chart_{&phi_, {}}, psi_chart_{&psi_, {}},
      boost_(s.num_faces(), 1.0), hinge_angle_(min_angle_), cg_steps_(options.linear_solver == "cg") {
  if (seams_ == nullptr) return;
  phi_chart_.map = psi_chart_.map = std::vector<Scalar>(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v) phi_chart_.map[v] = psi_chart_.map[v] = {v};
  fixed_tips_ = FixedTips(*seams_);
  for (const auto& pair : seams_->cut->copy_pairs()) {
    const double sign = seams_->sign[pair.path];
    if (pair.minus == pair.plus) continue;
    phi_chart_.map[pair.plus] = {pair.minus, sign, seams_->phi_offset[pair.path]};
    psi_chart_.map[pair.plus] = {pair.minus, sign, seams_->psi_offset[pair.path]};
  }
  std::vector<Eigen::Vector3d> tips;
  for (const int v : fixed_tips_) tips.push_back(s.position(v));
  spacing_target_ = ConeSpacingTargets(geo, tips, options.tip_cone_radius, h);
}

LevelSetProblem::LevelSetProblem(const LevelSetProblem& o, LevelSetSolution* into)
    : s_(o.s_), geo_(o.geo_), edges_(o.edges_), g_(o.g_), options_(o.options_), w_(o.w_), h_(o.h_),
      min_angle_(o.min_angle_), seams_(o.seams_), seam_terms_(o.seam_terms_), solution_(into), phi_(into->phi),
      psi_(into->psi), phi_chart_{&phi_, o.phi_chart_.map}, psi_chart_{&psi_, o.psi_chart_.map},
      fixed_tips_(o.fixed_tips_), spacing_target_(o.spacing_target_), boost_(o.boost_), hinge_angle_(o.hinge_angle_),
      barrier_floor_(o.barrier_floor_), prefix_(o.prefix_), cg_steps_(o.cg_steps_) {}

void LevelSetProblem::Project() {
  if (seams_ == nullptr) return;
  ProjectTransitions(*seams_, seams_->phi_offset, &phi_);
  ProjectTransitions(*seams_, seams_->psi_offset, &psi_);
}

LevelSetMetrics LevelSetProblem::Measure() const {
  return levelset_internal::Measure(s_, geo_, g_, phi_, psi_, options_.min_angle);
}

void LevelSetProblem::HoldTips(ceres::Problem* problem) const {
  for (const int v : fixed_tips_)
    for (double* x : {&phi_[v], &psi_[v]})
      if (problem->HasParameterBlock(x)) problem->SetParameterBlockConstant(x);
}

// Smoothness across the seams: f on the minus side, g on the plus side; with the plus face's
// third vertex l read as s·(u_l − a) (its plus-chart value mapped back), the ordinary
// smoothness term measures ∇u_f − s·∇u_g, the jump in one chart.
void LevelSetProblem::AddSeamSmoothness(TermProblem* terms, const Chart& u, const std::vector<double>& offsets,
                                        const std::vector<char>* live) const {
  if (w_.smoothness <= 0.0) return;
  for (const auto& t : seam_terms_) {
    if (!Live(live, {t.i_minus, t.j_minus, t.k, t.l})) continue;
    const double sign = seams_->sign[t.path];
    Scalar l = u.At(t.l);
    l = {l.vertex, sign * l.scale, sign * (l.offset - offsets[t.path])};
    terms->AddSmoothnessBlock(AddMapped(&terms->problem, SmoothnessResidual::Create(t.Gf, t.Gg, t.area, t.distance, h_),
                                       terms->Weight(w_.smoothness),
                                       {{&u, u.At(t.i_minus)}, {&u, u.At(t.j_minus)}, {&u, u.At(t.k)}, {&u, l}}));
  }
}

// φ's terms: alignment + spacing + smoothness.
void LevelSetProblem::AddPhiTerms(TermProblem* terms, const std::vector<char>* live) const {
  ceres::Problem* problem = &terms->problem;
  for (int f = 0; f < s_.num_faces(); ++f) {
    const auto ids = s_.face_vertices(f);
    if (!Live(live, {ids[0], ids[1], ids[2]})) continue;
    if (w_.alignment > 0.0 && g_.weight[f] > 0.0)
      AddMapped(problem, AlignmentResidual::Create(geo_.G[f], g_.direction[f], g_.weight[f], s_.face_area(f), h_),
                terms->Weight(w_.alignment),
                {{&phi_chart_, phi_chart_.At(ids[0])}, {&phi_chart_, phi_chart_.At(ids[1])},
                 {&phi_chart_, phi_chart_.At(ids[2])}});
  }
  AddSpacing(s_, geo_, h_, w_.spacing, phi_chart_, spacing_target_, terms, live);
  AddSmoothness(edges_, h_, w_.smoothness, phi_chart_, terms, live);
  if (seams_ != nullptr) AddSeamSmoothness(terms, phi_chart_, seams_->phi_offset, live);
}

// ψ's terms: conjugacy + transversality (both also involve φ) + spacing + smoothness.
void LevelSetProblem::AddPsiTerms(TermProblem* terms, const std::vector<char>* live) const {
  ceres::Problem* problem = &terms->problem;
  for (int f = 0; f < s_.num_faces(); ++f) {
    const auto ids = s_.face_vertices(f);
    if (!Live(live, {ids[0], ids[1], ids[2]})) continue;
    const std::initializer_list<std::pair<const Chart*, Scalar>> blocks{
        {&phi_chart_, phi_chart_.At(ids[0])}, {&phi_chart_, phi_chart_.At(ids[1])},
        {&phi_chart_, phi_chart_.At(ids[2])}, {&psi_chart_, psi_chart_.At(ids[0])},
        {&psi_chart_, psi_chart_.At(ids[1])}, {&psi_chart_, psi_chart_.At(ids[2])}};
    const Eigen::Vector3d& n = s_.face_normal(f);
    if (w_.conjugacy > 0.0)
      AddMapped(problem, ConjugacyResidual::Create(geo_.G[f], n, geo_.S[f], geo_.flat_curvature, s_.face_area(f)),
                terms->Weight(w_.conjugacy), blocks);
    if (w_.transversality > 0.0)
      AddMapped(problem, TransversalityResidual::Create(geo_.G[f], n, hinge_angle_, s_.face_area(f), h_),
                terms->Weight(w_.transversality * boost_[f]), blocks);
    if (barrier_floor_ != kNoFloor)
      AddMapped(problem, CrossingBarrierResidual::Create(geo_.G[f], n, min_angle_, barrier_floor_, s_.face_area(f), h_),
                terms->Weight(w_.transversality), blocks);
  }
  AddSpacing(s_, geo_, h_, w_.spacing, psi_chart_, spacing_target_, terms, live);
  AddSmoothness(edges_, h_, w_.smoothness, psi_chart_, terms, live);
  if (seams_ != nullptr) AddSeamSmoothness(terms, psi_chart_, seams_->psi_offset, live);
}

// 1. φ alone.
Status LevelSetProblem::SolvePhi() {
  TermProblem terms(cg_steps_);
  AddPhiTerms(&terms);
  HoldTips(&terms.problem);
  if (terms.problem.NumResidualBlocks() > 0)
    PQ_RETURN_IF_ERROR(levelset_internal::Solve(prefix_ + "phi", options_.max_iterations, &terms,
                                                &solution_->solver[prefix_ + "phi"]));
  Project();
  return Status::Ok();
}

// 2. ψ with φ held.
Status LevelSetProblem::SolvePsi() {
  TermProblem terms(cg_steps_);
  AddPsiTerms(&terms);
  for (double& value : phi_)
    if (terms.problem.HasParameterBlock(&value)) terms.problem.SetParameterBlockConstant(&value);
  HoldTips(&terms.problem);
  if (terms.problem.NumResidualBlocks() > 0)
    PQ_RETURN_IF_ERROR(levelset_internal::Solve(prefix_ + "psi", options_.max_iterations, &terms,
                                                &solution_->solver[prefix_ + "psi"]));
  Project();
  return Status::Ok();
}

// 3. Both together, so that φ can give way where ψ cannot cross it steeply enough.
Status LevelSetProblem::SolveJoint() {
  if (options_.joint_iterations <= 0) return Status::Ok();
  TermProblem terms(cg_steps_);
  AddPhiTerms(&terms);
  AddPsiTerms(&terms);
  HoldTips(&terms.problem);
  PQ_RETURN_IF_ERROR(
      levelset_internal::Solve(prefix_ + "joint", options_.joint_iterations, &terms,
                               &solution_->solver[prefix_ + "joint"], true));
  Project();
  return Status::Ok();
}

namespace {

// The cone's whole solve (to the joint, from the initial guess) on its own φ, ψ and Ceres
// summaries, so that it can run beside the first layout's: TryTipCone merges what it keeps.
struct ConeSolve {
  LevelSetSolution solution;
  std::unique_ptr<LevelSetProblem> problem;
  Status status;
  bool rounds_done = false;  // its rounds run too (alongside: they are the same whenever run)
};

// What SolveOnMesh keeps for its `finish` (on the heap: with `finish` it outlives the call).
struct MeshSolveState {
  LevelSetGeometry geo;
  std::vector<InteriorEdge> edges;
  std::vector<SeamEdgeTerm> seam_terms;  // the same for both solves
  LevelsetOptions plain, cone;     // without and with levelset.tip_cone_radius
  std::vector<double> phi0, psi0;  // the initial guess
  std::unique_ptr<LevelSetProblem> problem;
  std::unique_ptr<ConeSolve> cone_solve;  // solved alongside the first (levelset.alongside), or null
  // The cone's solve on its thread (with cone_solve), until TryTipCone joins it or, not needed,
  // cancels it. Last: destroyed first, so that a solve still running is cancelled and joined
  // before anything it reads goes.
  std::unique_ptr<AlongsideSolve> alongside;
};
// From the initial guess to the joint solve, into *out with its problem in *problem; prefix: the
// solves' names in the log and report ("cone_" for the retry, so that it does not overwrite the
// first layout's entries).
using WholeSolve = std::function<Status(const LevelsetOptions&, const std::string& prefix, LevelSetSolution* out,
                                        std::unique_ptr<LevelSetProblem>* problem)>;

// Whether a layout with `tips` branch points may be solved again with the cone: the one gate
// of the retry (TryTipCone) and of its solve alongside the first layout (SolveOnMesh).
bool MayRetryWithCone(const LevelsetOptions& options, int tips) { return options.tip_cone_radius > 0.0 && tips > 0; }

// 5. The cone's retry (levelset.tip_cone_radius): a layout with branch points that ends, after
// its rounds, with a fold-over or a face below min_angle is solved again from the initial
// guess with the spacing term following the cone round each branch point (ConeSpacingTargets),
// and the better end by RoundsKey is kept. Every face the rounds leave below min_angle on the
// Great Court's meshes lies within ~1.5 h of a branch point, where level lines h apart can only
// shear the cells; with the cone everywhere, 14 of 14 such runs crossed at ≥ 30°, but the
// corpus' layouts were a different draw (2 runs fewer met every target, 1.7 % softer), so the
// cone is the retry, not the default (benchmarks/RESULTS.md, "The cone's spacing round the
// branch points"). Layouts that meet min_angle are untouched. From the initial guess, not
// from where the first layout ended: that retry (the joint solve and its rounds only) was as
// stiff and 1.5× cheaper on the corpus, but the 962k-triangle Great Court's curvature layout
// then ended at 26.8° instead of 31.0° (RESULTS, "The cone's second solve from where the
// first ended: tried, not kept"). The cone's solve usually ran alongside the first, its rounds
// too (StartConeAlongside); else it is solved here, once it is known to be needed.
Status TryTipCone(MeshSolveState& state, const WholeSolve& solve, LevelSetSolution* solution) {
  const LevelSetMetrics without = solution->metrics;
  const double min_angle = state.plain.min_angle;
  if (!MayRetryWithCone(state.cone, state.problem->NumTips()) ||
      (without.foldovers == 0 && without.faces_below_min_angle == 0) || CrossingOutOfReach(without)) {
    state.alongside.reset();  // not needed: cancelled (its Ceres solve ends within one iteration) and joined
    return Status::Ok();
  }
  const bool alongside = state.alongside != nullptr;  // its solve ran on a second thread (report.json)
  if (alongside) state.cone_solve->status = state.alongside->Join();
  state.alongside.reset();
  // Alongside, the cone's rounds usually ran too; else they run here.
  std::unique_ptr<ConeSolve> cone = std::move(state.cone_solve);
  LOG(INFO) << "levelset: " << without.faces_below_min_angle << " faces cross below " << min_angle << "° (the worst at "
            << without.min_crossing_angle_deg << "°, " << without.foldovers << " fold-overs); "
            << (cone ? "taking the second solve, alongside it, with" : "solving again with")
            << " the cone's spacing within " << state.cone.tip_cone_radius << " h of its " << state.problem->NumTips()
            << " branch points";
  if (!cone) {
    cone = std::make_unique<ConeSolve>();
    cone->status = solve(state.cone, "cone_", &cone->solution, &cone->problem);
  }
  PQ_RETURN_IF_ERROR(cone->status);
  if (!cone->rounds_done) PQ_RETURN_IF_ERROR(cone->problem->Rounds());
  const LevelSetMetrics with = cone->problem->Measure();
  const bool kept = RoundsKey(with, min_angle) < RoundsKey(without, min_angle);
  solution->solver.update(cone->solution.solver);  // its solves' entries, all "cone_"
  solution->tip_cone = {{"tried", true}, {"kept", kept}, {"radius_h", state.cone.tip_cone_radius},
                        {"alongside", alongside},
                        {"min_crossing_without", without.min_crossing_angle_deg},
                        {"min_crossing_with", with.min_crossing_angle_deg},
                        {"area_below_without", without.area_below_min_angle},
                        {"area_below_with", with.area_below_min_angle},
                        {"foldovers_without", without.foldovers}, {"foldovers_with", with.foldovers}};
  LOG(INFO) << "levelset: with the cone " << with.min_crossing_angle_deg << "° (" << with.faces_below_min_angle
            << " faces below, " << with.foldovers << " fold-overs), without " << without.min_crossing_angle_deg
            << "°: " << (kept ? "the cone's layout kept" : "the first layout kept");
  if (!kept) return Status::Ok();
  solution->phi = std::move(cone->solution.phi);
  solution->psi = std::move(cone->solution.psi);
  solution->crossing_rounds_kept = cone->solution.crossing_rounds_kept;
  solution->metrics = with;
  return Status::Ok();
}

// Starts the cone's whole solve and its rounds (TryTipCone) on a thread of its own beside the
// first layout's, if the layout may need it and levelset.alongside has a core to spare
// (AlongsideBudget): from SolveOnMesh's start, or, where the budget was spent then (the poles'
// layout solved alongside: levelset_poles.cc), again before the first layout's rounds, once
// its joint solve has ended below min_angle or folded (else no rounds run and the cone is not
// needed). It runs until TryTipCone joins it or, not needed, cancels it. Its rounds are the
// ones TryTipCone would run: the same whichever thread runs them.
void StartConeAlongside(MeshSolveState* state, const WholeSolve& solve, const LevelsetOptions& options) {
  if (state->alongside != nullptr) return;
  state->cone_solve = std::make_unique<ConeSolve>();
  state->alongside = std::make_unique<AlongsideSolve>();
  ConeSolve* cone = state->cone_solve.get();
  const LevelsetOptions* cone_options = &state->cone;
  const auto whole = [cone, cone_options, solve] {
    PQ_RETURN_IF_ERROR(solve(*cone_options, "cone_", &cone->solution, &cone->problem));
    PQ_RETURN_IF_ERROR(cone->problem->Rounds());
    cone->rounds_done = true;
    return Status::Ok();
  };
  if (!state->alongside->Start(whole, AlongsideBudget(options))) {
    state->alongside.reset();
    state->cone_solve.reset();
  }
}

}  // namespace

// The level sets on the mesh they are solved on (see SolveLevelSets for the working mesh).
// seams: null, or the seams s is the cut surface of, with their signs (SolveWithSeams); the
// offsets are set here. With branch points and levelset.alongside (AlongsideBudget), the cone's solve
// (TryTipCone) runs on a second thread beside the first layout's joint solve and its rounds,
// until TryTipCone knows whether it is needed: then joined, or cancelled within one Ceres
// iteration (not joined as soon as the first joint solve ended, which made the first layout
// wait for a solve that was then thrown away). It reads s, g, seams and the state's inputs,
// none of which the first layout writes; s, g and seams must outlive *finish, as the rounds
// already required (the state, and with it the thread, goes with *finish): a caller that keeps
// them in the same closure as *finish must destroy *finish first (SolveOnWorking's WorkingFinish).
Status SolveOnMesh(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                   LevelSetSeams* seams, LevelSetSolution* solution, Finish* finish) {
  if (seams != nullptr && seams->cut == nullptr) seams = nullptr;
  // On the heap: with `finish` the problem outlives this call.
  auto state = std::make_shared<MeshSolveState>();
  state->geo = Precompute(s);
  state->edges = InteriorEdges(s, state->geo);
  PQ_RETURN_IF_ERROR(InitialGuess(s, state->geo, state->edges, g, options, h, seams, solution));
  if (seams != nullptr) state->seam_terms = SeamEdgeTerms(s, state->geo, *seams->cut);
  state->plain = state->cone = options;
  state->plain.tip_cone_radius = 0.0;
  state->phi0 = solution->phi;
  state->psi0 = solution->psi;
  // The whole solve from the initial guess to the joint (φ and ψ alone first with
  // levelset.separate_solves; the rounds come with `finish`).
  // Reads s, g, seams and *state, writes only *out and *problem: two can run at once.
  // A raw state: the cone's thread holds a copy, and must not own the state that joins it.
  const WholeSolve solve = [state = state.get(), &s, &g, h, seams](const LevelsetOptions& o, const std::string& prefix,
                                                                   LevelSetSolution* out,
                                                                   std::unique_ptr<LevelSetProblem>* problem) {
    out->phi = state->phi0;
    out->psi = state->psi0;
    *problem = std::make_unique<LevelSetProblem>(s, state->geo, state->edges, g, o, h, seams, state->seam_terms, out);
    (*problem)->SetSolvePrefix(prefix);
    (*problem)->Project();
    if (prefix.empty()) out->initial = (*problem)->Measure();  // the same initial guess for the retry
    if (o.separate_solves) {
      PQ_RETURN_IF_ERROR((*problem)->SolvePhi());
      PQ_RETURN_IF_ERROR((*problem)->SolvePsi());
    }
    return (*problem)->SolveJoint();
  };
  const int tips = seams != nullptr ? static_cast<int>(FixedTips(*seams).size()) : 0;
  const bool may_retry = MayRetryWithCone(options, tips);
  if (may_retry) StartConeAlongside(state.get(), solve, options);
  PQ_RETURN_IF_ERROR(solve(state->plain, "", solution, &state->problem));
  const auto rounds = [state, solve, solution, may_retry, options]() {
    const LevelSetMetrics joint = state->problem->Measure();
    if (may_retry && (joint.foldovers > 0 || joint.faces_below_min_angle > 0) && !CrossingOutOfReach(joint))
      StartConeAlongside(state.get(), solve, options);
    PQ_RETURN_IF_ERROR(state->problem->Rounds());
    solution->metrics = state->problem->Measure();
    return TryTipCone(*state, solve, solution);
  };
  if (finish == nullptr) return rounds();
  solution->metrics = state->problem->Measure();
  *finish = rounds;
  return Status::Ok();
}

}  // namespace levelset_internal
}  // namespace pqlayout
