// Which free edges to brace (`extract.brace_free_edges: paying`, decided in stage `stiffen`):
// a free stretch's quads are cut into triangles (geometry/edge_bracing.h) only if the shell
// the evaluator makes of it is stiffer. Greedy, stretch by stretch in FreeEdgeQuads' order:
// with the stretches kept so far cut, cut this one too, evaluate (the stage: stiffen, then
// C = fᵀu of the frame), and keep it if C drops by at least kBracingGain (1 %) below the best
// so far. The diagonals' own weight is in the load, so a stretch whose long rim cells cost
// more steel than they brace is refused by the same number.
// Why after stiffen and not on the extracted mesh: on the barrel with free gables, cutting
// both gable rows lowers the planarised shell's C by 1.2 % but the stiffened shell's by 47 %
// (× 0.53; stiffen can shape the shell once its edges are trusses), and one gable alone on
// the extracted mesh by 0.2–1 %: a trial on the extracted mesh braces nothing there
// (measured, benchmarks/RESULTS.md "Free edges braced where it pays").
// Cutting a planar quad leaves two planar triangles: a planarised mesh stays planar.
#pragma once

#include <functional>
#include <vector>

#include "base/status.h"
#include "geometry/quad_extraction.h"
#include "solver/frame_analysis.h"

namespace pqlayout {

inline constexpr double kBracingGain = 0.01;
inline constexpr int kMaxBracingTrials = 8;  // stretches tried one by one; beyond, all of them at once

// Per mesh vertex: on the reference boundary (origin) and restrained in no direction.
std::vector<bool> FreeBoundaryVertices(const ExtractedMesh& mesh, const std::vector<Restraints>& restraints);

// Evaluates a candidate in place (e.g. stiffens it) and returns its compliance, J.
using BracingEvaluator = std::function<Status(ExtractedMesh* candidate, double* compliance)>;

struct BracingChoice {
  int stretches = 0;            // free stretches with quads on them
  int braced_stretches = 0;     // ... cut
  int braced_quads = 0;
  int trials = 0;               // evaluations, the unbraced one first
  int kept_trial = 0;           // which evaluation the result is
  double compliance_unbraced = 0.0, compliance = 0.0;  // J, as the evaluator measured them
  std::vector<double> ratio;    // per trial after the first: C / best C before it
};

// mesh: the unbraced candidate; on return the kept trial as the evaluator left it. The
// unbraced evaluation's error is returned; a trial's error counts as "does not pay", unless
// the run was interrupted (CheckInterrupt), which is returned.
Status BraceWherePays(const std::vector<bool>& free, const BracingEvaluator& evaluate, ExtractedMesh* mesh,
                      BracingChoice* choice);

}  // namespace pqlayout
