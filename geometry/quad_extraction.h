// Quad-dominant mesh from two families of level lines (paper §3.1 step 3, SPEC stage 5
// `extract`): the curves φ = i and ψ = j (i, j integers; with |∇φ| ≈ 1/h they lie h metres
// apart) are intersected with each other and with the boundary, and neighbouring
// intersection points are connected along the curves and along the boundary.
//
// Method. Every reference triangle is cut along all integer levels of φ, then of ψ
// (Sutherland–Hodgman clipping; φ and ψ are linear on a triangle, so the pieces are convex
// polygons), each piece labelled by its cell (⌊φ⌋, ⌊ψ⌋) by construction. A face of the
// output is a connected set of pieces with the same label (joined across shared piece edges);
// its boundary loop keeps only the output vertices: points where three or more cells meet
// (a φ line crosses a ψ line, a level line meets the reference boundary — the outside counts
// as a cell) and boundary corners. Cut points are keyed symbolically, never by position: a reference vertex,
// (reference edge, family, level) or (face, i, j); every decision about a shared point is
// made from values computed once per key, so neighbouring triangles agree. Ties follow
// geometry/level_lines.h: a value exactly equal to a level counts as above it.
// Afterwards edges shorter than min_edge × h are collapsed (boundary corners stay, boundary
// vertices stay on the boundary, the link condition keeps the mesh manifold); a quad that
// loses a vertex becomes a triangle. Boundary vertices that no interior edge reaches and that
// lie on a straight piece of the boundary are dropped. Where both families cross the
// boundary obliquely, a boundary triangle and pentagon sharing a curve's last segment are
// re-split into two well-shaped quads when possible. Faces keep the reference orientation.
//
// Where a region of one label is not a disc (it surrounds a hole of the surface or an
// island of another cell) it cannot be one polygon: it is left out and counted.
//
// Seams (geometry/seams.h). With a SeamCut, φ and ψ are given per vertex of the cut surface
// and jump across every seam path p: u₊ = s_p·u₋ + a_p (φ) or + b_p (ψ). The triangles of the
// cut surface are cut as above, then the two sides of every seam are identified
// symbolically ("cut, then identify"): a vertex copy with its twin copy, the point (minus
// edge, family, level L) with (plus edge, family, s·L + offset); pieces are joined across a
// seam edge when their labels correspond under the transition ((i, j) ↔ (i + a, j + b) for
// s = +1, (a − i − 1, b − j − 1) for s = −1). Everything after that (loops, output points,
// collapses, boundary fixes, splits) sees one seamless polygon mesh; seam edges never count
// as reference boundary. At the tip of a seam with s = −1 (a ±½ singularity) the mesh gets
// an irregular vertex or cell (a branch point).
#pragma once

#include <map>
#include <vector>

#include <Eigen/Core>

#include "geometry/closest_point.h"
#include "geometry/mesh.h"
#include "geometry/seams.h"
#include "base/status.h"
#include "geometry/surface_model.h"

namespace pqlayout {

// Where an output vertex lies on the reference surface: a triangle and barycentric
// coordinates in the order of surface.face_vertices(face).
struct QuadMeshVertex {
  int face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  bool on_boundary = false;  // on the reference boundary
  bool corner = false;       // a boundary corner of the reference surface
  bool centre = false;       // added by the clean-up at the centre of a large cell (not a crossing)
  bool cap = false;          // on the ring of a cap that closes a pole (geometry/cap_fill.h)
};

struct ExtractionStats {
  int regions_with_holes = 0;  // label regions that are not discs (left out)
  int rejected_faces = 0;      // polygons OpenMesh refused (would be non-manifold)
  int collapsed_edges = 0;     // short edges merged
  int padded_faces = 0;        // loops with fewer than 3 output vertices, given extra points
  int dropped_boundary_vertices = 0;  // idle straight-boundary vertices removed (valence 2, no corner)
  int dropped_interior_vertices = 0;  // interior valence-2 vertices removed (DropInteriorValence2Vertices)
  int moved_onto_boundary = 0;  // interior vertices moved onto a chord's new point (RefineBoundaryChords)
  int resplit_boundary_pairs = 0;  // boundary triangle + pentagon pairs re-split into two quads
  int collapsed_boundary_triangles = 0;  // crossings just inside the boundary moved onto it
  int split_interior_polygons = 0;       // interior 6- and 8-gons cut into quads
  int centre_vertices = 0;               // ... of them around a new vertex at their centre
  int split_boundary_polygons = 0;       // boundary 6- to 10-gons cut into quads (and a triangle)
  int floating_faces = 0;  // faces of parts that touch no reference boundary (dropped: nothing holds them)
  int refined_boundary_edges = 0;        // boundary vertices inserted where a chord left a curved boundary
  int slid_boundary_vertices = 0;        // boundary vertices moved along the boundary to even out chords
  int caps = 0;                          // holes of poles closed by one polygon (geometry/cap_fill.h)
  int braced_quads = 0;                  // quads on a free edge cut into two triangles (geometry/edge_bracing.h)
  // Seams: piece edges on a seam with no piece of the corresponding cell on the other side
  // (0 when the values satisfy the transitions; otherwise the mesh has a slit there).
  int unmatched_seam_edges = 0;
  double seam_transition_mismatch = 0.0;  // max |u₊ − (s·u₋ + offset)| over seam vertex copies (levels)
};

struct ExtractedMesh {
  PolyMesh mesh;                        // double points, faces oriented like the reference
  std::vector<QuadMeshVertex> origin;   // per mesh vertex
  ExtractionStats stats;
};

// A hole the level-set stage cut round a pole (problems/levelset.h, LevelSetCap), closed
// after extraction by one cap face (geometry/cap_fill.h).
struct CapHole {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

// surface: the reference triangles; phi, psi: one value per vertex (#V), their integer
// levels are the curves; corner_angle_deg: boundary turning angle above which a reference
// boundary vertex is a corner (kept as a mesh vertex); min_edge_length (metres, the stage
// passes extract.min_edge × h): shorter edges are collapsed, 0 keeps all;
// pair_boundary_triangles: where a boundary triangle and a boundary pentagon share the last
// segment of a curve, re-split the hexagon they form into two quads (the curve then ends at
// the neighbouring boundary point); caps: the holes round poles — a boundary loop of
// `surface` whose vertices all lie within radius + cap_reach of a cap's centre is a cap's rim,
// a jagged loop of working-mesh edges that a cap face will close: its kinks are no corners (as
// corners they stay mesh vertices, and a level line ending next to one leaves a short rim
// edge whose collapse turns a rim quad into a triangle, interior once the cap is closed).
// reference: where `surface` is a working mesh (remeshed or holed), the surface the output will
// be moved onto (PlacedOnReference): every vertex is moved there before the clean-up, so that
// short edges and angles are judged where they will lie — the Reading Room's ring is a polygon
// on a working mesh, and a boundary vertex moved out onto the ring shortened a 0.21 h edge to
// 0.198 h after the collapses. Barycentric origins stay on `surface`.
// InvalidInput on size mismatch or non-finite values.
Status ExtractQuadMesh(const SurfaceModel& surface, const std::vector<double>& phi, const std::vector<double>& psi,
                       double corner_angle_deg, double min_edge_length, ExtractedMesh* out,
                       bool pair_boundary_triangles = true, const std::vector<CapHole>& caps = {},
                       double cap_reach = 0.0, const SurfaceModel* reference = nullptr);

// Transitions across the seams of `cut`, per path p: u₊ = sign[p]·u₋ + offset[p] with u = φ
// (phi_offset) or ψ (psi_offset), "minus" the side of SeamEdge::minus_face. sign ±1 (shared
// by φ and ψ), offsets whole numbers of levels.
struct SeamTransitions {
  const SeamCut* cut = nullptr;
  std::vector<int> sign;
  std::vector<int> phi_offset, psi_offset;
};

// The same on a surface cut open along seams. surface: the original (uncut) reference
// surface, whose faces the cut shares; phi_cut, psi_cut: one value per vertex of
// seams.cut->cut(). The values must satisfy the transitions within
// kSeamTransitionTolerance (relative, in levels): they are then made to satisfy them
// exactly (the plus copy takes s·u₋ + offset; a single-copy tip of a sign −1 seam takes
// offset / 2). Output origins refer to `surface`'s faces (the cut's faces have the same
// indices and corner order). InvalidInput on size mismatch, non-finite values, a bad
// transition or values that violate one.
Status ExtractQuadMesh(const SurfaceModel& surface, const SeamTransitions& seams, const std::vector<double>& phi_cut,
                       const std::vector<double>& psi_cut, double corner_angle_deg, double min_edge_length,
                       ExtractedMesh* out, bool pair_boundary_triangles = true, const std::vector<CapHole>& caps = {},
                       double cap_reach = 0.0, const SurfaceModel* reference = nullptr);
constexpr double kSeamTransitionTolerance = 1e-6;

// What the stage reports about an extracted mesh (lengths in metres).
struct ExtractedMeshMetrics {
  int n_vertices = 0, n_edges = 0, n_faces = 0;
  int euler_characteristic = 0;  // V − E + F
  int boundary_loops = 0;
  double quad_fraction = 0.0;                 // faces with 4 sides / all faces
  std::map<int, int> face_sides;              // number of sides → faces
  std::map<int, int> vertex_valence;          // valence → vertices
  double edge_min = 0.0, edge_mean = 0.0, edge_max = 0.0;
  double planarity_max = 0.0, planarity_mean = 0.0;  // δ (PlanarityDelta)
  double boundary_deviation_vertices = 0.0;  // max distance of a mesh boundary vertex to the reference boundary
  double boundary_deviation_edges = 0.0;     // ... of any point of a mesh boundary edge (chord sagitta)
  int n_reference_corners = 0;               // boundary corners of the reference surface
  int n_corner_vertices = 0;                 // ... that are mesh vertices
  // Faces that are not quads and touch no boundary vertex, caps aside: sides and centroid.
  std::vector<std::pair<int, Eigen::Vector3d>> interior_non_quads;
  std::vector<std::pair<int, Eigen::Vector3d>> caps;  // the caps of poles (geometry/cap_fill.h)
};

// Where an extracted vertex at p lies on `reference`: boundary vertices (corners aside) at the
// closest point of its boundary, the others at the closest point of the surface; the element
// is the reference triangle there.
SurfacePoint PlacedOnReference(const ClosestPointQuery& reference, const QuadMeshVertex& origin,
                               const Eigen::Vector3d& p);

// Why the extraction's short-edge collapse would not merge the ends of mesh edge (u, v) (a
// sentence), or null if it would (the edge was made after the collapses, by the boundary
// clean-up or the chord refinement).
const char* ShortEdgeBlocker(const ExtractedMesh& extracted, int u, int v);

ExtractedMeshMetrics MeasureExtractedMesh(const SurfaceModel& surface, const ExtractedMesh& extracted,
                                          double corner_angle_deg);

}  // namespace pqlayout
