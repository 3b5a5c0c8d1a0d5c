// Caps: the holes that the level-set stage's poles leave in the mesh it is solved on
// (problems/levelset.h, LevelSetCap) closed in the extracted mesh, one polygon each: the
// crown ring of a ribbed dome, where the fanning family's lines end.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "geometry/quad_extraction.h"

namespace pqlayout {

// Every boundary loop of `out` whose vertices all lie within radius + reach of a cap's centre
// becomes one face (oriented like its neighbours); its vertices are then interior (origin
// on_boundary false, cap true). A loop vertex that only the cap and one other face use (a
// kink of the hole's jagged rim that no level line reaches) is dropped from both. The first
// row of cells is merged into the cap if every vertex of it lies within `row` of the rim (a
// ring line close to the hole leaves slivers there). Returns the number of caps closed.
int FillCaps(const std::vector<CapHole>& caps, double reach, double row, ExtractedMesh* out);

// Whether face f of the mesh is a cap (a polygon of more than four sides on cap vertices only).
bool IsCapFace(const ExtractedMesh& mesh, FaceHandle f);

}  // namespace pqlayout
