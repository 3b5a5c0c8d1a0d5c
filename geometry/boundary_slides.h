// The boundary slides of the chord refinement (boundary_refinement.h): boundary vertices
// moved along the reference boundary so that fewer chords need a new vertex, onto sharp
// kinks, or to shorten a chord. Internal to the refinement (boundary_refinement.cc), apart
// to keep each file short.
#pragma once

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "geometry/quad_extraction.h"
#include "geometry/reference_boundary.h"

namespace pqlayout::boundary_internal {

inline constexpr double kGoodAngle = 20.0 * M_PI / 180.0;  // pieces with every angle in [20°, 160°] first
inline constexpr int kMaxPieces = 8;  // a chord is never cut into more pieces than this while sliding
inline constexpr double kSlideMargin = 0.1;  // a slid vertex keeps this fraction of the span from either neighbour
// A vertex moved onto a kink may make the faces at it up to this much worse than
// min(20°, what they had): a hole's boundary makes reflex corners that a few degrees change.
inline constexpr double kKinkAngleSlack = 3.0 * M_PI / 180.0;

// The boundary between two points of one loop, the shorter way round: the walk starts at arc
// `from` and goes forward by `span`; a_first says whether it starts at a (else at b).
struct Span {
  bool ok = false;
  bool a_first = true;
  double from = 0.0, span = 0.0;
};

Span Between(const ReferenceBoundary& boundary, const ReferenceBoundary::Location& a,
             const ReferenceBoundary::Location& b);

// The boundary loops of a mesh given as halfedge → face, each in the faces' orientation and
// starting at a corner if it has one.
std::vector<std::vector<int>> MeshBoundaryLoops(const std::map<std::pair<int, int>, int>& face_of,
                                                const std::vector<QuadMeshVertex>& origin);

// Slides boundary vertices (not corners) along the boundary so that fewer chords need an
// extra vertex. Greedy along each mesh boundary loop, starting at a corner if it has one:
// a vertex keeps its place if its chord from the previous (already placed) vertex is within
// tolerance there, else it moves back to the farthest place where it is; where the chord
// needs extra vertices anyway, the vertex moves as far forward as those allow (slack for
// the chords that follow). Every vertex stays within max_slide (arc length) of where the
// level lines put it and keeps kSlideMargin of the span to its neighbours; a move that
// would give a face at the vertex an angle below min(20°, what it had), or an edge at it
// shorter than min(min_edge, what it had), is undone.
// Returns the number of vertices moved.
int SlideBoundaryVertices(const ReferenceBoundary& boundary, double tolerance, double max_slide, double min_edge,
                          const std::vector<std::vector<int>>& faces,
                          const std::map<std::pair<int, int>, int>& face_of, std::vector<Eigen::Vector3d>* position,
                          std::vector<QuadMeshVertex>* origin);

// Moves boundary vertex v by `move` (signed arc length) along reference loop `loop` from arc
// `arc`, onto a kink, unless it is pinned or the move would give a face at it an angle more
// than kKinkAngleSlack below min(20°, what it had) or an edge at it shorter than
// min(min_edge, |move|, what it had): the alternative, a vertex inserted at the kink, would
// make an edge |move| long. A moved vertex is pinned. Returns whether it moved.
bool SlideToKink(const ReferenceBoundary& boundary, int loop, double arc, double move, int v, double min_edge,
                 const std::vector<std::vector<int>>& faces, std::vector<Eigen::Vector3d>* position, std::vector<QuadMeshVertex>* origin,
                 std::vector<bool>* pinned);

// The chord a – b (its boundary `span`) lengthened: the end at span.from moves `back` along the
// boundary away from the other, the other end `forward` (a pinned end's share goes to the
// other), so that the pieces it is then cut into are no shorter than min_edge. All or none, each
// at most max_slide and as SlideToKink accepts the shape, but with no edge at it ending shorter
// than min(min_edge, what it had). Returns the vertices moved (pinned), none if it could not.
// (The corpus' two openings: a pentagon's chord 0.38 h long cut into two 0.19 h pieces.)
inline constexpr double kRoomFactor = 1.02;  // pieces aimed at this × min_edge of arc: a chord is shorter than its arc
std::vector<int> WidenChord(const ReferenceBoundary& boundary, int loop, const Span& span, int a, int b, double back,
                            double forward, double max_slide, double min_edge, const std::vector<std::vector<int>>& faces,
                            std::vector<Eigen::Vector3d>* position, std::vector<QuadMeshVertex>* origin,
                            std::vector<bool>* pinned);

// A kink of the reference boundary that turns by θ with min_edge · sin(θ/2) > tolerance (5.7°
// at the defaults) is followed within tolerance only by chords shorter than min_edge on one
// side of it, unless a mesh vertex sits at it: the corpus's openings are polygons with 21°
// kinks 0.2–0.4 h apart. Each boundary vertex (not a corner) within min_edge of such a kink
// moves onto it, if the kink is less than halfway to either boundary neighbour and SlideToKink
// accepts the shape. Returns the number of vertices moved.
int SnapToSharpKinks(const ReferenceBoundary& boundary, double min_turn, double min_edge,
                     const std::vector<std::vector<int>>& faces, const std::map<std::pair<int, int>, int>& face_of,
                     std::vector<Eigen::Vector3d>* position, std::vector<QuadMeshVertex>* origin,
                     std::vector<bool>* pinned);

// A chord a – b (its boundary `span`) beyond tolerance whose equal pieces would be shorter
// than min_edge (a chord just longer than a small opening allows; the caller asks only where
// a new vertex would not make quads): one end slides along the
// boundary towards the other, at most max_slide, until the chord is within tolerance — the end
// whose move is shorter first, each if SlideToKink accepts the shape; the neighbouring chord
// takes the slack (and is cut if it must, into longer pieces). Returns the vertex moved, or −1.
int ShortenChord(const ReferenceBoundary& boundary, int loop, const Span& span, int a, int b, double tolerance,
                 double max_slide, double min_edge, const std::vector<std::vector<int>>& faces,
                 std::vector<Eigen::Vector3d>* position, std::vector<QuadMeshVertex>* origin,
                 std::vector<bool>* pinned);

}  // namespace pqlayout::boundary_internal
