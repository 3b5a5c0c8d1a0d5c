// Evenly spaced streamlines of a per-face LINE field on a triangle surface, after
// B. Jobard and W. Lefer, "Creating evenly-spaced streamlines of arbitrary density" (1997),
// for the top-view figures (paper Fig. 6: integral curves of the guidance field).
//
// The roofs are height fields, so the tracing happens in the xy projection: each triangle
// is projected to the plane and carries its direction projected to xy and normalised
// (constant per face). Faces whose projected area is ~0 (vertical walls, folds seen
// edge-on) or whose direction projects to ~0 (a singularity, a vertical direction) carry
// no field: a line stops there and no line starts there. So do the faces around the
// singular vertices of the line field (non-zero index, e.g. the four sources of Fig. 6),
// which a line would otherwise pass straight through. Where projected triangles overlap
// (not a height field) the first one found is used.
//
// d and -d are the same line direction: every step is aligned with the previous one.
// A line grows both ways from its seed with midpoint (RK2) steps and stops at the
// boundary (clipped onto it), at a face without field, where it turns by more than
// max_turn_deg within dsep of its length (it is passing a singularity), when it comes
// closer than dtest = test_ratio · dsep to another line (or to a far part of itself), or
// at the length cap. Seeds: a fixed grid with spacing dsep, and after each accepted line
// the points at distance dsep on both sides of it (breadth-first), each valid only if at
// least dsep away from every line. Deterministic for a given input.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "geometry/line_field_singularities.h"
#include "geometry/surface_model.h"

namespace pqlayout {

struct StreamlineOptions {
  double separation = 1.0;            // dsep, metres: distance between neighbouring lines
  double test_ratio = 0.5;            // dtest = test_ratio · dsep stops a line near another
  double step_ratio = 0.1;            // integration step = step_ratio · dsep
  double min_length_ratio = 1.0;      // lines shorter than this · dsep are dropped
  double max_length_ratio = 4.0;      // a line grows at most this × the bbox diagonal per side
  double max_turn_deg = 60.0;         // turning more than this within dsep ends a line
  double min_projected_norm = 1e-3;   // |d_xy| / |d| below this: no field on the face
  bool stop_at_singularities = true;  // no field on the faces around vertices of non-zero
                                      // index (FindLineFieldSingularities), e.g. sources
  // Those singularities if the caller has found them already (FindLineFieldSingularities of the
  // same surface and directions, default length bound; the guidance stage's), else null: found
  // here (~0.17 s at a million triangles).
  const std::vector<LineFieldSingularity>* singularities = nullptr;
};

// Evenly spaced polylines (xy, metres) of the line field `directions` (one 3D vector per
// face, any length and sign). Returns no lines if options are invalid (dsep <= 0) or the
// sizes do not match.
std::vector<std::vector<Eigen::Vector2d>> EvenlySpacedStreamlines(
    const SurfaceModel& surface, const std::vector<Eigen::Vector3d>& directions,
    const StreamlineOptions& options);

}  // namespace pqlayout
