// Stage `guidance` (paper §2.2 "Principal Strains" and §3, SPEC §3): a unit direction per
// face for the level-set layout to follow, and a weight saying how much alignment matters.
//   strain:    e_max of the Green–Lagrange tensor of the membrane solution (eigenvalue of
//              largest modulus), oriented so that ⟨e_max, P v⟩ > 0 (paper); magnitude |ε_max|.
//   curvature: the principal curvature direction of largest |κ| of the face shape operator
//              (the paper's reference layout); magnitude |κ1 − κ2|.
//   file:      per-face CSV `id,dx,dy,dz[,weight]`, projected onto the face plane.
// Weight: 0 where magnitude < threshold × scale, ramping linearly to 1 at (threshold + ramp)
// × scale; scale = max |ε_max| for strain, the 95th percentile of |κ1| + |κ2| for curvature
// (so an umbilic surface such as a sphere gets no alignment anywhere, and a few sharply
// curved faces do not set the scale for the whole roof).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/surface_model.h"
#include "problems/options.h"

namespace pqlayout {

struct GuidanceField {
  std::vector<Eigen::Vector3d> direction;  // per face: unit, in the face plane
  std::vector<double> major, minor;        // per face: principal values (strains, or curvatures)
  std::vector<double> magnitude;           // per face: what the weight is measured on
  std::vector<double> weight;              // per face: alignment weight in [0, 1]
  double scale = 0.0;                      // the reference the threshold is relative to
};

// The alignment weight of each magnitude (see above).
std::vector<double> AlignmentWeights(const std::vector<double>& magnitude, double scale, double threshold, double ramp);

Status ComputeStrainGuidance(const SurfaceModel& surface, const std::vector<double>& v_z,
                             const GuidanceOptions& options, GuidanceField* field);
Status ComputeCurvatureGuidance(const SurfaceModel& surface, const GuidanceOptions& options, GuidanceField* field);
Status ReadGuidanceFile(const SurfaceModel& surface, const GuidanceOptions& options, GuidanceField* field);

}  // namespace pqlayout
