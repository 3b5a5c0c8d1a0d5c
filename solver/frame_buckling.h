// Linear buckling of a frame (issue 18): the load factors λ at which the frame, loaded by
// λ × its load case, loses stability, from (K + λ K_G(N)) φ = 0, where K is the frame's
// elastic stiffness and K_G the geometric stiffness of its members under the axial forces N
// of the linear solve (solver/beam_element.h, LocalGeometricStiffness).
// Solved as the generalised symmetric eigenproblem −K_G φ = μ K φ, μ = 1/λ, for the largest
// μ (Spectra's Lanczos, SymGEigsSolver in regular-inverse mode: K⁻¹ by CHOLMOD, K positive
// definite once the frame is supported), which is the shift-invert around λ = 0 that the
// smallest positive factors need. μ ≤ 0 throughout means no positive factor: the load does
// not compress the frame enough to buckle it ("no buckling under this load"), not a
// negative factor. Member buckling between nodes and lateral–torsional buckling are not
// modelled (one element per member).
#pragma once

#include <string>
#include <vector>

#include "base/status.h"
#include "solver/frame_analysis.h"

namespace pqlayout {

struct BucklingResult {
  bool buckles = false;                           // a positive factor exists
  std::vector<double> factors;                    // λ₁ ≤ λ₂ ≤ …, all positive
  std::vector<std::vector<NodeVector>> modes;     // per factor, per node; max |translation| = 1
  int operations = 0;                             // K⁻¹ products (Lanczos)
};

// modes ≥ 1: how many of the smallest positive factors to find (fewer if the frame has fewer).
Status SolveBuckling(const FrameModel& model, const FrameResult& linear, int modes, BucklingResult* result);

// The last buckling solve, kept: `stiffen` checks the shell it ends with, and `analyze` then
// checks the same frame under the same axial forces, bit for bit; that second Lanczos run
// (~0.1 s on the Great Court) is skipped. The inputs are compared as bytes (nodes, members,
// restraints, section, material, axial forces, modes), so anything that differs in one bit is
// solved anew.
class BucklingMemo {
 public:
  // SolveBuckling, or the kept result when the inputs are those of the last call; *reused says which.
  Status Solve(const FrameModel& model, const FrameResult& linear, int modes, BucklingResult* result, bool* reused);

 private:
  std::string key_;
  BucklingResult result_;
};

}  // namespace pqlayout
