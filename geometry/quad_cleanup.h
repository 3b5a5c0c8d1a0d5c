// The clean-up of an extracted polygon mesh (quad_extraction.h): short edges collapsed, interior
// kinks and idle boundary vertices dropped, boundary triangle/pentagon pairs re-split into
// quads, boundary corner triangles moved onto the boundary, interior 6/8-gons cut into quads. Internal to
// the extraction (quad_extraction.cc); the counts it returns are ExtractionStats.
#pragma once

#include <set>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "geometry/quad_extraction.h"

namespace pqlayout::extraction_internal {

struct Polygons {
  std::vector<Eigen::Vector3d> position;
  std::vector<QuadMeshVertex> origin;
  std::vector<std::vector<int>> faces;
};

inline constexpr double kMinResplitAngle = 20.0 * M_PI / 180.0;  // both quads: every angle in [20°, 160°]
// SplitLargePolygons' floor for a boundary cell of seven or more sides (no cut above min_angle).
inline constexpr double kLastResortCutAngle = 10.0 * M_PI / 180.0;

// One round of collapses of edges shorter than min_length, on disjoint neighbourhoods.
int CollapseRound(double min_length, Polygons* m);

// Why CollapseRound will not collapse edge (u, v) (a sentence), or null if it would.
const char* CollapseBlocker(const Polygons& m, int u, int v);

// Drops vertices no face uses.
void Compact(Polygons* m);

// Parts of the mesh (faces connected through shared vertices) with no vertex on the reference
// boundary float: where the level sets fold over, cells that are not discs are left out and
// can ring an island of cells that no support can hold (a mechanism for the frame analysis).
// Their faces are removed; returns how many.
int DropFloatingParts(Polygons* m);

// Boundary vertices that no interior edge reaches (valence 2, one face), are no corner and
// lie on a straight piece of the boundary (a curve that touched the boundary and left it
// again, or the end of a merged sliver) carry nothing: removed from their face.
int DropIdleBoundaryVertices(Polygons* m);

// A vertex off the boundary with two neighbours (a crossing left with only two of its four
// segments by the short-edge collapses, or where two curves touch without crossing) is a kink
// in one frame member and nothing else: it is removed from its two faces, which then share the
// chord between its neighbours (a triangle there disappears: with a pentagon it leaves a
// quad). Two triangles on such a vertex are left alone. Returns the number dropped.
int DropInteriorValence2Vertices(Polygons* m);

// Along a boundary crossed obliquely by both families the boundary cells alternate between
// triangles and pentagons. A triangle and a pentagon sharing a curve segment that ends on the
// boundary form a hexagon, which is re-split into two quads by the diagonal that gives the
// best-shaped quads (every angle between 20° and 160° in the hexagon's plane): the last segment of that curve then
// ends at the neighbouring boundary point. Returns the number of re-split pairs.
int ResplitBoundaryTrianglePentagonPairs(Polygons* m);

// Where two curves cross just inside the boundary, the corner they cut off is a boundary
// triangle (A, B on the boundary, X the crossing) between two boundary cells of five or more
// sides. Moving the crossing onto the boundary (X and B merged into A, or X and A into B,
// whichever gives the better-shaped faces, every quad angle within [min_angle, 180° −
// min_angle]) removes the triangle and makes both neighbours one side shorter: a triangle and
// two pentagons become two quads. Boundary corners are never merged away.
int CollapseBoundaryTriangles(double min_angle, Polygons* m);

// The smallest corner angle (ShapeAngle) over a cut of `face` into `pieces`, or −1 if a
// diagonal of the cut is already an edge elsewhere (it would be doubled) or, with
// `on_boundary` given, joins two boundary vertices (it would run along or across the
// boundary).
double CutScore(const Polygons& m, const std::vector<int>& face, const std::vector<std::vector<int>>& pieces,
                const std::set<std::pair<int, int>>& halfedges, const std::vector<char>* on_boundary);

// SplitLargePolygons' last resorts for an interior cell (geometry/quad_cleanup_vertices.cc):
// CentreSplit (a 6- or 8-gon round a new centre vertex) and QuadAndCentreSplit (an 8-gon: a
// quad cut off, the hexagon left round a centre vertex). Each appends its quads to `faces`
// and the vertex to m, or changes nothing and returns false.
bool CentreSplit(const std::vector<int>& face, const std::set<std::pair<int, int>>& halfedges, double min_angle,
                 double min_edge, Polygons* m, std::vector<std::vector<int>>* faces);
bool QuadAndCentreSplit(const std::vector<int>& face, const std::set<std::pair<int, int>>& halfedges,
                        double min_angle, double min_edge, Polygons* m, std::vector<std::vector<int>>* faces);

// Cells that are large polygons are cut into quads by the diagonals that give the
// best-shaped quads, if every quad angle is within [min_angle, 180° − min_angle]:
// - a cell that touches no boundary and has 6 or 8 sides (where the curves fan out around a
//   singularity of the guidance): 2 or 3 quads, the singularity then a vertex of valence 3 or
//   5, as in any quad mesh; failing that 3 or 4 quads around a new centre vertex (marked
//   `centre`: the caller puts it on the surface) at the corners' average or the best place
//   near it, none of its edges shorter than min_edge;
// - a boundary cell of 6 to 10 sides (a level line that turned back near the boundary):
//   quads, plus one triangle cut off at a boundary vertex if the number of sides is odd (so
//   that every cell off the boundary stays a quad); no diagonal
//   joins two boundary vertices. A large unbraced panel is both hard to make planar and
//   the softest part of the frame.
// Returns the number of interior and of boundary cells cut.
std::pair<int, int> SplitLargePolygons(double min_angle, Polygons* m, double min_edge = 0.0);

}  // namespace pqlayout::extraction_internal
