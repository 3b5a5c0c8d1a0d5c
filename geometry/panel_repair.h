// Panels that planarisation degenerated, repaired topologically. On a net that is not conjugate enough, planarisation makes
// some quads planar by running two of their vertices into each other (or past each other,
// folding the panel): such a quad is a triangle with a joint in one corner. CloseShortEdges
// makes that explicit: the two ends of every edge shorter than min_length become one vertex,
// by the extraction's collapse rules (geometry/quad_cleanup.h, CollapseRound: a corner or
// boundary vertex keeps its place, no collapse that would pinch the mesh, disjoint
// neighbourhoods per round), so the quad is the triangle it has become, a pentagon a quad,
// and two vertices that slid past each other are one again; a chord between two boundary
// vertices that the rules refuse loses the ear on its far side first (panel_repair.cc,
// DropEarsOfShortChords). The caller planarises again.
// CutDarts: a planar quad with one reflex corner (a dart: δ, which measures the distance
// between the diagonals' lines, cannot see it) is cut along the diagonal from that corner
// into the two convex triangles it is made of; the vertices do not move, so nothing needs
// planarising again.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "geometry/quad_extraction.h"

namespace pqlayout {

// Returns the number of edges closed. `start`: one position per vertex of *mesh (e.g. where
// the extraction put it), carried along to the vertices that remain.
int CloseShortEdges(double min_length, ExtractedMesh* mesh, std::vector<Eigen::Vector3d>* start);

// Returns the number of darts cut (each then two triangles).
int CutDarts(ExtractedMesh* mesh);

// SplitFoldedPanels: a polygon that planarisation folded (FoldedSince, polygon_shape.h, against
// `start`) is cut into the fan of triangles, from the corner whose fan is the least folded now
// (the largest smallest signed area round the polygon's normal at `start`): triangles need
// no planarity, so the next planarisation can open them again (it holds every triangle
// open: problems/residuals/triangle_orientation_residual.h). Returns the number of polygons
// cut; vertices neither move nor change number.
int SplitFoldedPanels(const std::vector<Eigen::Vector3d>& start, ExtractedMesh* mesh);

// SplitWarpedPanels: before planarisation, a quad whose planarity δ (geometry/planarity.h) is
// above max_delta — its diagonals further apart than max_delta × their mean length — is cut
// into the two triangles of the diagonal whose smallest corner angle is the larger (not along
// a diagonal that is an edge already, nor into a triangle facing against the quad's normal).
// Flattening such a quad moves its vertices far (on the Great Court × strain ensemble up to 2
// edge lengths), which folds and shortens its neighbours' edges; cut, it needs no planarity.
// max_delta ≤ 0: nothing. Returns the number of quads cut; vertices neither move nor change number.
int SplitWarpedPanels(double max_delta, ExtractedMesh* mesh);

}  // namespace pqlayout
