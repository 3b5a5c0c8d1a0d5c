// Bracing of free edges (`extract.brace_free_edges`: `all` in stage extract, `paying` in
// stage stiffen): a quad with an edge on a free (unsupported) stretch of the boundary is cut
// into two triangles by the diagonal that gives the better-shaped pair. An unbraced quad row
// along a free edge is a mechanism-like strip in the frame (its members bend); the diagonal
// makes it a truss. Which stretches are worth it is the frame's question
// (problems/edge_bracing_choice.h); here only the topology.
#pragma once

#include <vector>

#include "geometry/quad_extraction.h"

namespace pqlayout {

// free: per mesh vertex, whether it lies on a free stretch of the boundary (on the reference
// boundary with no restraint). A quad is on a free edge if one of its edges is a mesh boundary
// edge whose both ends are free. Returns those quads (face indices) grouped by free stretch
// (a connected run of free boundary edges; it ends at a supported vertex), a quad on two
// stretches in the first one's group. Groups in order of their first face.
std::vector<std::vector<int>> FreeEdgeQuads(const std::vector<bool>& free, const PolyMesh& mesh);

// Cuts the given quads (face indices of out->mesh; other faces and non-quads are left as they
// are) by their better diagonal. Vertices are kept (origins stay valid). Returns the number
// cut (also added to out->stats.braced_quads).
int CutQuads(const std::vector<int>& faces, ExtractedMesh* out);

// Every quad on a free edge cut (FreeEdgeQuads, then CutQuads). Returns the number cut.
int BraceFreeEdges(const std::vector<bool>& free, ExtractedMesh* out);

}  // namespace pqlayout
