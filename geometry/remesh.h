// Isotropic remeshing of a reference surface to a target edge length (CGAL Polygon Mesh
// Processing: split long edges, collapse short ones, flip for valence, tangential
// relaxation, projection back onto the input). The boundary is remeshed as constrained
// polylines (its vertices slide along it) and boundary corners (turning angle above
// corner_angle) stay where they are. Used to give the level-set solve a working mesh whose
// resolution follows the layout spacing h, not the resolution of a fine reference.
#pragma once

#include "geometry/mesh.h"
#include "base/status.h"
#include "geometry/surface_model.h"

namespace pqlayout {

// Mean edge length of the mesh (metres).
double MeanEdgeLength(const TriMesh& mesh);

// `iterations` rounds of CGAL's isotropic remeshing towards `edge_length` (metres).
// InvalidInput if edge_length is not positive; Internal if CGAL leaves a mesh that
// SurfaceModel would refuse.
Status RemeshIsotropic(const SurfaceModel& surface, double edge_length, double corner_angle_deg, int iterations,
                       TriMesh* out);

}  // namespace pqlayout
