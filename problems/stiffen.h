// Stage `stiffen` (SPEC §6b; the paper's §5 future work: "a shape optimization step, in
// which the geometry itself is treated as variable, within tolerances describing the
// architect's willingness to accept modifications"). The planarised mesh's vertices move
// so that the compliance C = fᵀu of the frame that `analyze` builds (problems/grid_frame.h,
// the same model, loads that follow the geometry) drops, subject to
//   - planarity: δ ≤ 0.9 × planarize.target_delta on every sub-quad of every face;
//   - tolerance, hard: each vertex moves in a box of its own frame (two tangents and the
//     normal of the reference at the planarised vertex's foot point f): ±stiffen.slide along
//     each tangent (at most 0.1 h), ±S along the normal with S = t − 1.5 r, r the largest
//     rise or fall of the reference off the tangent plane under the box's tangential square
//     (sampled on a 3 × 3 grid); a point of the box is then within |c| + r ≤ t of the
//     reference. The box's eight corners are also measured exactly: one beyond t (a box that
//     reaches past the reference's boundary, where no rise sees it) halves the slide, up to
//     three times (full, ½, ¼, ⅛), then none. The slide does not use up t = tolerance (it did while the box was inscribed
//     in the ball |p − f| ≤ t, which held the slide to ¼ t; a slide of 0.1 m instead of
//     0.01 m takes a further 16 % off the Great Court's compliance, README "Stiffen");
//   - boundary vertices (and joints that have one) held: on the reference boundary, corners
//     fixed; the frame's members and joints unchanged (hinges; while it runs the frame keeps
//     the start's joints, and a warning says if the final frame's differ);
//   - members no shorter than max(1.1 × section depth, stiffen.min_member × planarised
//     length) (EdgeLengthResidual hinge);
//   - panel kinks: the mesh polylines keep their planarised second differences
//     (FairnessChangeResidual, stiffen.weights.fairness, part of the objective).
//
// Method: L-BFGS (Ceres' GradientProblemSolver) on the planarity manifold:
//   F(z) = C(x)/C₀ + fairness change + member hinge + joint hinge,
//   x = f + R q per vertex, q = centre + radius ∘ sin z (BoxVariables): the box is built into
//   the variables, so the tolerance holds at every iterate without bounds (which Ceres'
//   line-search minimiser does not take);
//   planarity is a ceres::Manifold (problems/stiffen_manifold.h): every gradient and step
//   projected on the null space of the active sub-quads' Jacobian, every step retracted by
//   min-norm Gauss–Newton, so every iterate has δ ≤ 0.9 × target (+5 %). A start the
//   retraction cannot bring there (planarize stops at δ ≤ target) bounds each sub-quad it
//   leaves above by its own start δ instead (PlanarityManifold::AdmitStart): until 2026-12-07
//   such a start ended the stage at C × 1 (a warning) where it otherwise gains ~30 %.
// C and ∇C come from the adjoint (problems/grid_frame.h, one CHOLMOD factorisation per
// evaluation, the start's joints kept); the other terms are Ceres residual functors on the
// world positions whose cost and gradient ceres::Problem::Evaluate returns. The run ends when
// 20 iterations gain < 0.5 % of F (C/C₀ is then within 0.5 % of its converged value on the
// Great Court), after a fresh restart gains < 0.1 %, or after stiffen.max_iterations.
// RestorePlanarity (a Ceres least-squares projection inside the boxes) is the last resort if
// δ still exceeds the target.
// Why this method (README "Stiffen"): the augmented Lagrangian it replaced (the numpy
// prototype's method: planarity as PHR penalty terms) reached C × 0.74 at h = 3 m in 650
// evaluations and stalled at × 0.92 at h = 1.25 m: penalised, the planarity of thousands of
// sub-quads makes the Hessian ill-conditioned along the long-range moves that keep panels
// planar. Projected-gradient steps with planarity as a penalty gained 2 %; IPOPT would add a
// dependency for one stage. Joints whose vertices are all interior move (their edge kept
// below 0.9 × depth by a hinge); holding them instead cost 5 points of ratio on the strain
// grid (0.79 vs 0.74, measured with the augmented Lagrangian).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"
#include "problems/options.h"
#include "solver/frame_analysis.h"
#include "solver/frame_buckling.h"

namespace pqlayout {

struct StiffenReport {
  double compliance_before = 0.0, compliance_after = 0.0, compliance_ratio = 1.0;  // J, J, after/before
  double offset_max = 0.0, offset_mean = 0.0;      // |normal offset| from the planarised mesh, m
  double displacement_max = 0.0;                   // |p − p_planarised|, m
  double slide_max = 0.0;                          // its largest part along the reference (⊥ the normal), m
  double planarity_max = 0.0;                      // δ after
  double closeness_max = 0.0;                      // distance to the reference after, m
  double kink_mean_deg_before = 0.0, kink_max_deg_before = 0.0;  // angle between neighbouring face normals
  double kink_mean_deg_after = 0.0, kink_max_deg_after = 0.0;
  double steel_mass_change = 0.0;                  // (after − before) / before
  // The optimised shell could not be brought back within planarize.target_delta, or was
  // softer than its start, so the planarised one was kept (a warning says so; compliance_ratio
  // is then 1).
  bool kept_planarised = false;
  // Why the minimisation ended: "converged" (its window test), "no room" (every vertex held),
  // or the last L-BFGS run's Ceres message, e.g. a line search that found no step.
  std::string stop;
  double min_member_length = 0.0;                  // after, m
  int iterations = 0, evaluations = 0, held_vertices = 0;
  double seconds_frame = 0.0, seconds_ceres = 0.0;
  std::vector<double> normal_offset;               // per vertex, m (along the reference normal)
  // The engineering checks of the planarised and the stiffened frame (problems/structural_checks.h):
  // buckling_factor, utilisation_max, span_over_deflection each (null when not computed).
  nlohmann::json checks_before, checks_after;
  nlohmann::json ToJson() const;
};

// Per polygon-mesh interior edge: the angle between its two faces' normals, degrees.
std::vector<double> KinkAngles(const PolyMesh& mesh);

// Reshapes `mesh` (the planarised mesh; its origin flags say which vertices are on the
// boundary) in place. With options.tolerance = 0 the mesh is left as it is.
// memo (optional): the buckling checks before and after go through it (the last shell's is then
// analyze's, solver/frame_buckling.h).
Status StiffenMesh(const SurfaceModel& reference, const std::vector<Restraints>& vertex_restraints,
                   const AnalysisOptions& analysis, const StiffenOptions& options, double target_delta,
                   double spacing, ExtractedMesh* mesh, StiffenReport* report, BucklingMemo* memo = nullptr);

}  // namespace pqlayout
