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

}  // namespace pqlayout
