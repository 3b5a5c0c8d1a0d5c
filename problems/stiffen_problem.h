// The data of one stiffen run (problems/stiffen.h), shared by its objective and its driver:
// per vertex a local frame at its foot point on the reference and a box in it (the
// tolerance), which vertices are held, the faces and their sub-quads, the mesh polylines and
// their planarised second differences, and the members with their minimum lengths.
#pragma once

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

// The optimiser's variables: per free (not held) vertex three angles z, q = centre + radius ∘ sin z,
// so that every z lies in the box (the tolerance holds at every iterate, without bounds).
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

 private:
  const StiffenProblem& P_;
  std::vector<int> free_, index_;
};
void SetPoints(const std::vector<Eigen::Vector3d>& x, PolyMesh* mesh);
double MaxPlanarity(const StiffenProblem& P, const std::vector<Eigen::Vector3d>& x);

// Moves q as little as it can (anchor) until every face's δ ≤ target_delta, inside the boxes
// (Ceres: planarity within a shrinking budget, weight raised until met): the last resort when
// the manifold optimiser ends above the target.
Status RestorePlanarity(const StiffenProblem& P, double target_delta, std::vector<Eigen::Vector3d>* q);

}  // namespace pqlayout
