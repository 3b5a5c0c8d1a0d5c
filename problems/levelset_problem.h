// The level-set problem on one mesh, shared by its two files: levelset_problem.cc (the terms,
// the φ, ψ and joint solves, SolveOnMesh with the cone's second solve) and levelset_rounds.cc
// (the crossing and floor rounds after the joint solve).
#pragma once

#include <ceres/ceres.h>

#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include "problems/levelset_internal.h"

namespace pqlayout {
namespace levelset_internal {

inline constexpr double kNoFloor = -2.0;  // below any s_f: no barrier term

// What the solves on one mesh share: the charts of φ and ψ (seam transitions), the per-face
// transversality boost and hinge of the crossing rounds, and the term builders.
class LevelSetProblem {
 public:
  LevelSetProblem(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<InteriorEdge>& edges,
                  const GuidanceField& g, const LevelsetOptions& options, double h, LevelSetSeams* seams,
                  std::vector<SeamEdgeTerm> seam_terms, LevelSetSolution* solution);

  // Copies of seam vertices back onto their transitions (no-op without seams).
  void Project();
  LevelSetMetrics Measure() const;
  Status SolvePhi();
  Status SolvePsi();
  Status SolveJoint();
  Status Rounds();
  int NumTips() const { return static_cast<int>(fixed_tips_.size()); }  // branch points held at a/2
  // Prefixed to the names of the solves in the log and report.json's ceres (the cone's retry: "cone_").
  void SetSolvePrefix(const std::string& prefix) { prefix_ = prefix; }

 private:
  // A copy of `other` that solves into `into` (its φ, ψ there): Rounds' floor way, run on a
  // second thread beside the crossing rounds.
  LevelSetProblem(const LevelSetProblem& other, LevelSetSolution* into);
  Status CrossingRounds(const std::string& name = "crossing_round_", double floor = kNoFloor,
                        const std::function<void()>& each_round = {});
  Status FloorRounds();
  Status FloorWay();
  Status SolveLocal(const std::string& name, const std::vector<char>& live_phi, const std::vector<char>& live_psi,
                    double floor);
  // s_f of the transversality term on every face (crossing_barrier_residual.h).
  std::vector<double> SignedSines() const;
  // Closes a live set over the seam copies, so that every face whose values can move is in
  // it (and carries the barrier): a live copy frees its parameter, a live parameter moves
  // every copy of it.
  void CloseOverCopies(std::vector<char>* live) const;
  void AddPhiTerms(TermProblem* terms, const std::vector<char>* live = nullptr) const;
  void AddPsiTerms(TermProblem* terms, const std::vector<char>* live = nullptr) const;
  void AddSeamSmoothness(TermProblem* terms, const Chart& u, const std::vector<double>& offsets,
                         const std::vector<char>* live) const;
  void HoldTips(ceres::Problem* problem) const;

  const SurfaceModel& s_;
  const LevelSetGeometry& geo_;
  const std::vector<InteriorEdge> edges_;  // those the smoothness term acts on (SmoothedEdges)
  const GuidanceField& g_;
  const LevelsetOptions& options_;
  const LevelsetWeights& w_;
  const double h_, min_angle_;
  LevelSetSeams* seams_;  // null without seams
  const std::vector<SeamEdgeTerm> seam_terms_;
  LevelSetSolution* solution_;
  std::vector<double>& phi_;
  std::vector<double>& psi_;
  Chart phi_chart_, psi_chart_;
  std::vector<int> fixed_tips_;  // branch points of sign −1 seams: u = a/2 on both sides
  std::vector<double> spacing_target_;  // h|∇u| asked per face (ConeSpacingTargets; empty: 1)
  std::vector<double> boost_;    // per-face transversality weight factor (RaiseCrossings)
  double hinge_angle_;
  double barrier_floor_ = kNoFloor;  // CrossingBarrierResidual's floor t in FloorRounds
  std::string prefix_;
  const bool cg_steps_;  // levelset.linear_solver = cg (TermProblem)
};

// The branch points of sign −1 seams, held at a/2 by every solve (LevelSetProblem::NumTips).
std::vector<int> FixedTips(const LevelSetSeams& seams);

// The rounds' order of two ends (levelset_rounds.cc): smaller is better.
std::tuple<int, double, double> RoundsKey(const LevelSetMetrics& m, double min_angle_deg);

}  // namespace levelset_internal
}  // namespace pqlayout
