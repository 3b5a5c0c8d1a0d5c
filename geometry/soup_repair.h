// Repairs of a triangle soup read from a file that CAD exports commonly need and that have one
// right answer, made before validation (mesh_validation.h) so that OpenMesh still only sees
// checked input:
//   - unwelded seams: a surface exported patch by patch repeats each seam vertex once per patch,
//     at the same position or within rounding, and so is cut open along its seams (each seam a
//     boundary that would be supported). Boundary vertices that are not on a common triangle
//     and lie within the weld tolerance of each other become one vertex;
//   - T-junctions: patches tessellated at different densities put a vertex of one side in the
//     middle of an edge of the other. A boundary vertex within max(weld tolerance, 1e-3 × the
//     edge's length) of a boundary edge's interior splits that edge's triangle there;
//   - orientation: each connected part is oriented consistently and facing up (a roof exported
//     with its normals down is the same roof; its principal curvatures would change sign),
//     unless a part cannot be oriented at all (a Möbius band: validation refuses it).
// The weld tolerance is 1e-6 × the diagonal of the used vertices' bounding box (34 µm on a
// 34 m roof; float32 exports round at ~6e-8 of the coordinates). A soup that is not all
// triangles of three distinct existing vertices with finite coordinates is left as it is:
// validation names what is wrong with it.
#pragma once

#include "geometry/mesh_io.h"

namespace pqlayout {

struct SoupRepairs {
  int welded = 0;   // vertices merged into another
  int zipped = 0;   // T-junction vertices inserted into an edge of the other side
  int flipped = 0;    // triangles that disagreed with the rest of their part
  int turned_up = 0;  // parts that faced down, turned over as a whole
  double tolerance = 0.0;  // metres
  std::vector<int> vertex_of;  // per soup vertex, the vertex that now stands for it; empty: itself
};

// weld_tolerance > 0 replaces the default 1e-6 × diagonal (a CAD tessellation tolerance).
SoupRepairs RepairSurfaceSoup(PolygonSoup* soup, double weld_tolerance = 0.0);

// For a soup that still fails validation after the repairs: the farthest any boundary vertex
// lies off the interior of another side's boundary edge, counting only those within 5 % of
// that edge's length (a seam curved in elevation, tessellated coarsely on one side); 0 if
// none. A weld_tolerance of at least this closes every such T-junction.
double SuggestWeldTolerance(const PolygonSoup& soup);

}  // namespace pqlayout
