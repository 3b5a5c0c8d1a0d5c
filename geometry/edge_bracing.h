// Bracing of free edges (stage `extract`, `extract.brace_free_edges`): every quad with an edge
// on a free (unsupported) stretch of the boundary is cut into two triangles by the diagonal
// that gives the better-shaped pair. An unbraced quad row along a free edge is a mechanism-like
// strip in the frame (its members bend); the diagonal makes it a truss. Measured on the roof
// corpus (benchmarks/RESULTS.md): the barrel vault with free gables C × 0.53 (strain) and
// × 0.62 (curvature) after stiffen for 2.5–4 % more steel, the canopy × 0.96 and × 0.95; where
// the extra steel's own weight outweighs what the diagonals brace (the off-centre opening ×
// strain, C × 1.19 for 11 % more steel) it costs. Off by default: it trades quads for stiffness.
#pragma once

#include <vector>

#include "geometry/quad_extraction.h"

namespace pqlayout {

// free: per mesh vertex, whether it lies on a free stretch of the boundary (on the reference
// boundary with no restraint). A quad is cut if one of its edges is a mesh boundary edge whose
// both ends are free. Vertices are kept (origins stay valid). Returns the number of quads cut
// (also added to out->stats.braced_quads).
int BraceFreeEdges(const std::vector<bool>& free, ExtractedMesh* out);

}  // namespace pqlayout
