// The data of one stiffen run (problems/stiffen.h), shared by its objective and its driver:
// per vertex a local frame at its foot point on the reference and a box in it (the
// tolerance), which vertices are held, the faces and their sub-quads, the mesh polylines and
// their planarised second differences, and the members with their minimum lengths.
#pragma once

#include <algorithm>

#include <array>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "geometry/closest_point.h"
#include "geometry/quad_extraction.h"
#include "problems/options.h"
#include "problems/grid_frame.h"
#include "solver/framed_point_cost.h"

namespace pqlayout {

struct StiffenProblem {
  // Variables: per vertex, local coordinates q in its frame (p = f + R q) inside [lower, upper].
  std::vector<PointFrame> frames;
  std::vector<Eigen::Vector3d> lower, upper;
  std::vector<bool> held;                             // boundary (and joints with a boundary vertex), no room: p stays
  std::vector<std::vector<int>> faces;
  std::vector<std::array<int, 4>> sub_quads;          // every 4 vertices of a face in cyclic order
  std::vector<std::array<int, 3>> triples;            // mesh polylines a–v–b at valence-4 interior vertices
  std::vector<Eigen::Vector3d> second_difference0;    // their planarised second differences
  std::vector<std::tuple<int, int, double>> members;  // (i, j, minimum length)
  std::vector<std::tuple<int, int, double>> joint_edges;  // joints (edges shorter than the depth): (i, j, maximum length)
  double h = 1.0;
  StiffenWeights weights;
};

// Sets up P and the start q (in the boxes) from the planarised mesh and its frame model.
void SetUpStiffenProblem(const ClosestPointQuery& query, const ExtractedMesh& mesh, const GridFrame& frame,
                         const SectionOptions& section, const StiffenOptions& options, double spacing,
                         StiffenProblem* P, std::vector<Eigen::Vector3d>* q);

std::vector<Eigen::Vector3d> World(const StiffenProblem& P, const std::vector<Eigen::Vector3d>& q);

// The optimiser's variables: per free (not held) vertex three angles z, q = centre + radius ∘ sin(s z),
// so that every z lies in the box (the tolerance holds at every iterate, without bounds).
// s = min(1, L / radius) with L = StepScale(h) = max(0.1 h, 0.1 m): Ceres' line search takes its
// first step (and the first after each restart) at |Δz|∞ = 1, i.e. up to radius · sin 1 along
// the steepest component; with boxes of the scale the stage was tuned at (t = slide = 0.1 m at
// h = 1–3 m) s = 1 and nothing changes, but a box of metres made that step metres long: the
// Great Court's compliance ×0.34 at t = 0.5 m, ×0.36 at 2 m, ×0.39 at 5 m and ×1 at 50 m (the
// step failed the planarity retraction and the run ended at once). With s the first step
// moves a vertex at most L whatever the box (benchmarks/RESULTS.md, "Stiffen with more room").
class BoxVariables {
 public:
  explicit BoxVariables(const StiffenProblem& P);
  int size() const { return 3 * static_cast<int>(free_.size()); }
  const std::vector<int>& free() const { return free_; }
  int FreeIndex(int v) const { return index_[v]; }  // −1 for a held vertex
  std::vector<Eigen::Vector3d> Local(const double* z) const;          // q of every vertex (held: 0)
  std::vector<double> Parameters(const std::vector<Eigen::Vector3d>& q) const;  // z of q
  // ∂x_v/∂z_(k, c) for the free vertex v = free()[k].
  Eigen::Vector3d Derivative(int k, int c, const double* z) const;
  double Radius(int v, int c) const { return 0.5 * (P_.upper[v][c] - P_.lower[v][c]); }
  double Centre(int v, int c) const { return 0.5 * (P_.lower[v][c] + P_.upper[v][c]); }
  double Stretch(int v, int c) const { return std::min(1.0, step_scale_ / Radius(v, c)); }  // s (0 radius: 1)
  static double StepScale(double spacing) { return std::max(0.1 * spacing, 0.1); }

 private:
  const StiffenProblem& P_;
  double step_scale_;
  std::vector<int> free_, index_;
};
void SetPoints(const std::vector<Eigen::Vector3d>& x, PolyMesh* mesh);
double MaxPlanarity(const StiffenProblem& P, const std::vector<Eigen::Vector3d>& x);

// Moves q as little as it can (anchor) until every face's δ ≤ target_delta, inside the boxes
// (Ceres: planarity within a shrinking budget, weight raised until met): the last resort when
// the manifold optimiser ends above the target.
Status RestorePlanarity(const StiffenProblem& P, double target_delta, std::vector<Eigen::Vector3d>* q);

}  // namespace pqlayout
