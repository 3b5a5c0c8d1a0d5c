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

#include "geometry/line_field_singularities.h"
#include "geometry/surface_model.h"
#include "problems/options.h"

namespace pqlayout {

struct GuidanceField {
  std::vector<Eigen::Vector3d> direction;  // per face: unit, in the face plane
  std::vector<double> major, minor;        // per face: principal values (strains, or curvatures)
  std::vector<double> magnitude;           // per face: what the weight is measured on
  std::vector<double> weight;              // per face: alignment weight in [0, 1]
  double scale = 0.0;                      // the reference the threshold is relative to
  // With a fallback (AddCurvatureFallback): the source's own direction and weight per face,
  // before the blend (empty without one), so that the layout's alignment to the source alone
  // can be measured where the source is strong.
  std::vector<Eigen::Vector3d> source_direction;
  std::vector<double> source_weight;
  // The stage's field on the reference only: FindLineFieldSingularities(surface, direction), found
  // once by the guidance stage for its metrics, its figure, the level-set figure's guidance curves
  // and report.json's targets (~0.17 s each at a million triangles). Empty on the fields built
  // from it (AppendFace, the working mesh's transfer): those find their own.
  std::vector<LineFieldSingularity> singularities;
};

// Appends face f of `from` (every per-face field, the source ones if present) to `to`.
void AppendFace(const GuidanceField& from, int f, GuidanceField* to);

// The alignment weight of each magnitude (see above).
std::vector<double> AlignmentWeights(const std::vector<double>& magnitude, double scale, double threshold, double ramp);

Status ComputeStrainGuidance(const SurfaceModel& surface, const std::vector<double>& v_z,
                             const GuidanceOptions& options, GuidanceField* field);
Status ComputeCurvatureGuidance(const SurfaceModel& surface, const GuidanceOptions& options, GuidanceField* field);
// The curvature lines form a net: φ may follow either family, ψ then follows the other (the
// conjugate of a principal direction is the other one). The major direction (κ1 ≥ κ2 by
// sign) swaps family by 90° wherever κ1 − κ2 changes sign along a line, not at a point — a
// surface of revolution's meridian and parallel curvatures cross along a parallel (the
// off-centre opening's ring ridge: radial lines inside, circles outside, 14° alignment) — and
// no family of level lines can follow that jump. So the net is combed: faces are reached along
// a maximum spanning tree of the face graph keyed by the weaker weight of each pair (strong
// regions first, weak lines last), and each takes the family closer to its parent's. Where
// the major direction is continuous (isolated umbilics, every generic roof) only the faces at
// an umbilic's core would flip: parts of one choice smaller than min_area (the caller: h²)
// take the other, so there nothing changes. Faces of weight 0 keep their direction (nothing
// aligns to it; a nearly umbilic dome is weightless everywhere, and its layout stays as it
// was). Returns the number of faces whose family was swapped (their major and minor values
// swapped too).
int CombCurvatureNet(const SurfaceModel& surface, double min_area, GuidanceField* field);
Status ReadGuidanceFile(const SurfaceModel& surface, const GuidanceOptions& options, GuidanceField* field);

// The curvature fallback (guidance.fallback = curvature; beyond the paper). The paper aligns
// the layout only where the principal strain is strong and leaves the rest to the other
// terms; there the level lines wander (the strain field's weak zones are full of spurious
// singularities) and the cells come out sheared and warped. Here the principal curvature
// lines fill in, blended with the source as line fields (doubled angles), per face, in the
// face plane with e₁ = the source direction d_s and θ the angle of the curvature direction d_κ:
//   z = w_s·(1, 0) + w_c·(cos 2θ, sin 2θ),  w_c = (1 − w_s)·β·w_κ,
//   direction = e₁ rotated by ½ arg z (so ⟨direction, d_s⟩ ≥ 0: the source's orientation kept),
//   weight = min(1, |z|).
// Where w_s = 1 the source is unchanged; where w_s = 0 the face follows d_κ at β·w_κ. A face
// without a source direction, or without source weight, takes d_κ (even at weight 0: the
// line field's singularities, hence the seams, are those of the blend, so β = 0 is not the
// same as guidance.fallback = none). Measured (benchmarks/RESULTS.md, 2026-12-04): the
// Great Court's strain layout over 7 meshes, compliance after stiffen × 0.41 (median
// 158,262 → 65,051 J at β = 0.5). Returns the share of the area where w_c > w_s.
double AddCurvatureFallback(const SurfaceModel& surface, const GuidanceField& curvature, double beta,
                          GuidanceField* field);

}  // namespace pqlayout
