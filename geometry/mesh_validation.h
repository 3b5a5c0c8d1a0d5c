// Validation of a reference surface before it is turned into a half-edge mesh. The paper
// (§2.2) needs a manifold triangulation "without self-intersections, hanging edges,
// t-junctions, or isolated vertices"; a closed surface cannot be supported.
#pragma once

#include "geometry/mesh_io.h"
#include "geometry/status.h"

namespace pqlayout {

// Checks, in this order, and returns InvalidInput with one line naming the first offending
// element (the caller prefixes the file name):
//   empty mesh; non-finite vertex coordinates; faces that are not triangles or reference a
//   missing vertex; degenerate (zero-area) triangles; duplicate faces; non-manifold edges
//   (used by more than two faces, or inconsistently oriented); non-manifold vertices (whose
//   triangles do not form a single fan); a mesh without boundary.
Status ValidateSurfaceSoup(const PolygonSoup& soup);

}  // namespace pqlayout
