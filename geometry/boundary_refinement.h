// Mesh boundaries that follow a curved reference boundary (SPEC stage 5 `extract`).
//
// The extracted mesh's boundary vertices lie on the reference boundary, but its boundary
// edges are chords: along the Great Court's Reading Room ring (radius 22.2 m) a 3 m chord
// stands 0.05 m off the ring (sagitta L²/8R). RefineBoundaryChords inserts boundary
// vertices where a chord is further than a tolerance from the reference boundary and cuts
// the cell off by a diagonal from the new vertex, so that no cell gets three consecutive
// vertices on a curved boundary: the ring is a horizontal circle, and a panel with three
// of its vertices on it would have to be horizontal to be planar.
#pragma once

#include "geometry/quad_extraction.h"
#include "geometry/reference_boundary.h"
#include "geometry/surface_model.h"

namespace pqlayout {

// Keeps the mesh boundary within `tolerance` (metres) of the reference boundary, in two steps:
// 1. slides boundary vertices (not corners) along the boundary, at most max_slide (metres of
//    arc) from where the level lines end and never making an angle below 20° or an edge
//    below min_edge that was not there, so that fewer chords need a new vertex;
// 2. moves boundary vertices within min_edge of a sharp kink (SharpKinkTurn) onto it, then
//    splits every boundary edge still further than `tolerance` from the reference boundary at
//    the sharp kink of the boundary between its ends farthest from the edge, or, if there is
//    none, into the fewest pieces of equal arc length whose chords are within it (one vertex
//    at a time: the first piece, then the rest again), until none is, and cuts each
//    affected cell by the diagonal from the new vertex that gives the best pieces (ending at
//    an interior vertex if possible, then at least min_edge long, then all angles ≥ 20°,
//    then the most quads, then the best smallest angle).
// tolerance ≤ 0 does nothing. Returns the number of inserted vertices (also added to
// out->stats.refined_boundary_edges; moved vertices to out->stats.slid_boundary_vertices).
int RefineBoundaryChords(const SurfaceModel& surface, double tolerance, double max_slide, double min_edge,
                         ExtractedMesh* out);

}  // namespace pqlayout
