// Stage `stiffen` (SPEC §6b; the paper's §5 future work: "a shape optimization step, in
// which the geometry itself is treated as variable, within tolerances describing the
// architect's willingness to accept modifications"). The planarised mesh's vertices move
// so that the compliance C = fᵀu of the frame that `analyze` builds (problems/grid_frame.h,
// the same model, loads that follow the geometry) drops, subject to
//   - planarity: δ ≤ 0.9 × planarize.target_delta on every face (a penalty in each step, its
//     weight raised ×10 until the step meets it);
//   - tolerance, hard: each vertex moves in a box of its own frame (two tangents and the
//     normal of the reference at the planarised vertex's foot point f): ±stiffen.slide along
//     each tangent, ±S along the normal with S² = t² − (|a₀|+slide)² − (|b₀|+slide)², so
//     |p − f| ≤ t and the distance to the reference, ≤ |p − f|, never exceeds t = tolerance;
//   - boundary vertices and the vertices of joints (problems/grid_frame.h) held: on the
//     reference boundary, corners fixed, the frame's members and joints unchanged;
//   - members no shorter than max(1.1 × section depth, stiffen.min_member × planarised
//     length) (EdgeLengthResidual hinge);
//   - panel kinks: the mesh polylines keep their planarised second differences
//     (FairnessChangeResidual, stiffen.weights.fairness, part of the objective).
//
// Method: projected gradient with a smoothing metric, each step one Ceres least-squares
// solve. At iterate x_k with g = ∇C/C₀ (adjoint, one CHOLMOD factorisation) the step solves
//   min_x  ½ Σ_v |x_v − x_k,v + μ g_v|²/μ            (ProximalStepResidual: g·Δ + |Δ|²/2μ)
//        + ½ β/μ Σ_polylines |D²(x − x_k)|²          (smoothing metric, β = (ℓ/h)⁴, ℓ = stiffen.smoothing × h)
//        + fairness change + member hinge + planarity penalty,
//   x in the tolerance boxes (Ceres parameter bounds on the local coordinates),
// i.e. a proximal-gradient step on F = C/C₀ + fairness + hinge with the exact least-squares
// parts and the box handled by Ceres; g is replaced by the L-BFGS direction H g once a
// curvature pair exists (μ = 1 then). A step is kept when F falls (μ × 1.5), else retried
// shorter (μ × 0.3, or from the plain gradient after an L-BFGS step failed).
// MEASURED LIMIT (issue 16 stays open): on the Great Court (strain, h = 3 m, t = 0.1 m) this
// gains 2.3 % (C/C₀ 0.977), where the same iteration without planarity reaches 0.61 in 9
// steps: the planarity penalty in each step cuts the quasi-Newton direction to a sliver of
// itself, and the curvature pairs learn the unconstrained problem. Projecting the gradient
// onto the planarity constraints' tangent space first (tried: 0.960) breaks the use of the
// planarity budget. The next attempt should be an SQP step on the linearised planarity with
// multipliers, or an offset basis that is planar by construction. Why not the alternatives:
//   - Ceres' GradientProblem solvers take no constraints, and C is not a sum of squares (a
//     residual √C couples every vertex, a dense Jacobian row);
//   - an augmented Lagrangian around L-BFGS-B (the numpy prototype) stalled at 4,256
//     nodes: planarity and the tolerance fight the quasi-Newton model;
//   - IPOPT would add a dependency and a dense-ish Hessian approximation for one stage.
// Here the constraints are the planarize stage's own least-squares terms, solved exactly
// with sparse Cholesky every step, and the metric term makes each step smooth (the optimal
// change is smooth: 10–20 m on the Great Court), which keeps the iteration count from
// growing with the mesh.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"
#include "problems/config.h"
#include "solver/frame_analysis.h"

namespace pqlayout {

struct StiffenReport {
  double compliance_before = 0.0, compliance_after = 0.0, compliance_ratio = 1.0;  // J, J, after/before
  double offset_max = 0.0, offset_mean = 0.0;      // |normal offset| from the planarised mesh, m
  double displacement_max = 0.0;                   // |p − p_planarised|, m
  double planarity_max = 0.0;                      // δ after
  double closeness_max = 0.0;                      // distance to the reference after, m
  double kink_mean_deg_before = 0.0, kink_max_deg_before = 0.0;  // angle between neighbouring face normals
  double kink_mean_deg_after = 0.0, kink_max_deg_after = 0.0;
  double steel_mass_change = 0.0;                  // (after − before) / before
  double min_member_length = 0.0;                  // after, m
  int iterations = 0, evaluations = 0, rejected_steps = 0, held_vertices = 0;
  double seconds_frame = 0.0, seconds_ceres = 0.0;
  std::vector<double> normal_offset;               // per vertex, m (along the reference normal)
  nlohmann::json ToJson() const;
};

// Per polygon-mesh interior edge: the angle between its two faces' normals, degrees.
std::vector<double> KinkAngles(const PolyMesh& mesh);

// Reshapes `mesh` (the planarised mesh; its origin flags say which vertices are on the
// boundary) in place. With options.tolerance = 0 the mesh is left as it is.
Status StiffenMesh(const SurfaceModel& reference, const std::vector<Restraints>& vertex_restraints,
                   const AnalysisOptions& analysis, const StiffenOptions& options, double target_delta,
                   double spacing, ExtractedMesh* mesh, StiffenReport* report);

}  // namespace pqlayout
