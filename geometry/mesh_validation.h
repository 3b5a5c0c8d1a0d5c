// Validation of a reference surface before it is turned into a half-edge mesh. The paper
// (§2.2) needs a manifold triangulation "without self-intersections, hanging edges,
// t-junctions, or isolated vertices"; a closed surface cannot be supported.
#pragma once

#include "geometry/mesh_io.h"
#include "base/status.h"

namespace pqlayout {

// Checks, in this order, and returns InvalidInput with one line naming the first offending
// element (the caller prefixes the file name):
//   empty mesh; faces that are not triangles, reference a missing vertex or use one twice;
//   non-finite or implausible (beyond 1e8 m) coordinates of the vertices the faces use;
//   degenerate triangles (area ≤ 1e-12 × the squared diagonal of the used vertices' bounding
//   box); duplicate faces; non-manifold edges
//   (used by more than two faces, or inconsistently oriented); non-manifold vertices (whose
//   triangles do not form a single fan); a mesh without boundary.
Status ValidateSurfaceSoup(const PolygonSoup& soup);

// Coordinates are metres; beyond this a coordinate is a unit mistake (millimetres of a
// georeferenced model) and squared lengths start to lose every digit or overflow (the repairs'
// grid keys, coordinate / cell, too).
constexpr double kMaxSurfaceCoordinate = 1e8;

// The first of those checks, which the repairs (soup_repair.h) need to hold before they run:
// the mesh is not empty, its faces are triangles of three distinct existing vertices, and the
// vertices they use are finite and within kMaxSurfaceCoordinate; *diagonal is set to the
// diagonal of those vertices' bounding box.
Status CheckSoupFacesAndPoints(const PolygonSoup& soup, double* diagonal);

// For a soup read from binary float32 coordinates (binary STL or PLY): their spacing near the
// largest coordinate, against the mean edge length. Georeferenced coordinates in float32 lose
// the roof's shape (at 5,000 km they are 0.5 m apart): InvalidInput when the spacing exceeds
// 1 % of the mean edge; *warning (may be null) set from 0.01 % (0.1 mm on 1 m edges). Faces
// with an index out of range are skipped (validation names them).
Status CheckCoordinatePrecision(const PolygonSoup& soup, std::string* warning);

}  // namespace pqlayout
