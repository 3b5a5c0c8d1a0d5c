#include "geometry/boundary_refinement.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>
#include <map>
#include <optional>
#include <tuple>

#include "geometry/boundary_slides.h"
#include "geometry/polygon_shape.h"

namespace pqlayout {
namespace {

using namespace boundary_internal;


// Cuts face [b, v1, ..., vr, a] (its edge a → b closes the loop) at the new vertex m by m – v_j
// into [m, b, v1, ..., vj] and [vj, ..., vr, a, m], choosing j for: v_j not on the boundary,
// the new edge at least min_edge, both angles ≥ kGoodAngle, most quads, the largest angle.
void BestSplit(const std::vector<int>& loop, int m, const std::vector<Eigen::Vector3d>& position,
               const std::vector<QuadMeshVertex>& origin, double min_edge, std::vector<int>* best1,
               std::vector<int>* best2) {
  const int r = static_cast<int>(loop.size()) - 2;
  std::tuple<bool, bool, bool, int, double> best_key{false, false, false, -1, -INFINITY};
  for (int j = 1; j <= r; ++j) {
    std::vector<int> q1{m}, q2;
    for (int i = 0; i <= j; ++i) q1.push_back(loop[i]);
    for (int i = j; i <= r + 1; ++i) q2.push_back(loop[i]);
    q2.push_back(m);
    const double angle = std::min(ShapeAngle(position, q1), ShapeAngle(position, q2));
    const bool long_enough = (position[loop[j]] - position[m]).norm() >= min_edge;
    const std::tuple<bool, bool, bool, int, double> key{!origin[loop[j]].on_boundary, long_enough,
                                                        angle >= kGoodAngle,
                                                        int(q1.size() == 4) + int(q2.size() == 4), angle};
    if (key > best_key) best_key = key, *best1 = q1, *best2 = q2;
  }
}

// The fewest equal pieces (2 to kMaxPieces) into which the boundary from arc `from` forward by
// `span` must be cut for every piece's chord to lie within tolerance (kMaxPieces if none do).
int PiecesNeeded(const ReferenceBoundary& boundary, int loop, double from, double span, double tolerance) {
  for (int k = 2; k < kMaxPieces; ++k) {
    const double piece = span / k;
    bool within = true;
    for (int j = 0; j < k && within; ++j) {
      Eigen::Vector3d p, q;
      boundary.PointAt(loop, from + j * piece, &p);
      boundary.PointAt(loop, from + (j + 1) * piece, &q);
      within = boundary.ChordDeviation(p, q, loop, from + j * piece, piece) <= tolerance;
    }
    if (within) return k;
  }
  return kMaxPieces;
}

// The extracted mesh as plain polygons the refinement edits: positions, faces and which face
// each halfedge belongs to.
struct Polygons {
  std::vector<Eigen::Vector3d> position;
  std::vector<std::vector<int>> faces;
  std::map<std::pair<int, int>, int> face_of;  // halfedge → face

  explicit Polygons(const PolyMesh& mesh) {
    for (const auto v : mesh.vertices()) position.push_back(ToEigen(mesh.point(v)));
    for (const auto f : mesh.faces()) {
      std::vector<int> face;
      for (const auto v : mesh.fv_range(f)) face.push_back(v.idx());
      faces.push_back(std::move(face));
    }
    for (size_t f = 0; f < faces.size(); ++f) Register(int(f));
  }
  void Register(int f) {
    const auto& face = faces[f];
    for (size_t k = 0; k < face.size(); ++k) face_of[{face[k], face[(k + 1) % face.size()]}] = f;
  }
  // The mesh-boundary halfedges at vertex v (all of them if v < 0) whose ends are both on the
  // reference boundary (if on_boundary is given).
  void BoundaryHalfedges(int v, const std::vector<QuadMeshVertex>* on_boundary,
                         std::deque<std::pair<int, int>>* queue) const {
    for (const auto& [halfedge, f] : face_of) {
      if (face_of.count({halfedge.second, halfedge.first})) continue;
      if (v >= 0 && halfedge.first != v && halfedge.second != v) continue;
      if (on_boundary && !((*on_boundary)[halfedge.first].on_boundary && (*on_boundary)[halfedge.second].on_boundary))
        continue;
      queue->push_back(halfedge);
    }
  }
  // The vertex of face f off the boundary (v_j of [b, v1, ..., vr, a]) closest to p, if closer
  // than min_edge, moved onto p: the face is cut there into [b, v1, ..., v_j] and [v_j, ...,
  // vr, a] (a side with fewer than three vertices goes: its edge is then a boundary edge of
  // the neighbour), instead of a new vertex at p joined to v_j by an edge shorter than
  // min_edge. Not if a face at v_j would get an angle below min(kGoodAngle, what it had) or an
  // edge at v_j would be shorter than |p − v_j|. Returns v_j, or −1 (nothing changed).
  int MoveOntoBoundary(int f, int a, int b, const Eigen::Vector3d& p, const std::vector<QuadMeshVertex>& origin,
                       double min_edge) {
    std::vector<int> loop = faces[f];
    std::rotate(loop.begin(), std::find(loop.begin(), loop.end(), b), loop.end());
    int j = -1;
    for (int i = 1; i + 1 < static_cast<int>(loop.size()); ++i)
      if (!origin[loop[i]].on_boundary && (position[loop[i]] - p).norm() < min_edge &&
          (j < 0 || (position[loop[i]] - p).norm() < (position[loop[j]] - p).norm()))
        j = i;
    if (j < 0) return -1;
    const int v = loop[j];
    const double moved = (position[v] - p).norm();
    std::vector<int> at_v;  // the other faces at v
    for (size_t g = 0; g < faces.size(); ++g)
      if (int(g) != f && std::find(faces[g].begin(), faces[g].end(), v) != faces[g].end()) at_v.push_back(int(g));
    const std::vector<int> q1(loop.begin(), loop.begin() + j + 1), q2(loop.begin() + j, loop.end());
    const auto shape = [&](const std::vector<Eigen::Vector3d>& where) {
      double angle = INFINITY, edge = INFINITY;
      for (const int g : at_v) {
        const auto& face = faces[g];
        if (face.size() <= 4) angle = std::min(angle, ShapeAngle(where, face));
        const size_t k = std::find(face.begin(), face.end(), v) - face.begin(), n = face.size();
        edge = std::min({edge, (where[face[(k + 1) % n]] - where[v]).norm(), (where[face[(k + n - 1) % n]] - where[v]).norm()});
      }
      for (const auto* q : {&q1, &q2})
        if (q->size() >= 3) angle = std::min(angle, ShapeAngle(where, *q));
      return std::make_pair(angle, edge);
    };
    const double angle_before = shape(position).first;
    std::vector<Eigen::Vector3d> after = position;
    after[v] = p;
    const auto [angle_after, edge_after] = shape(after);
    if (angle_after < std::min(angle_before, kGoodAngle) || edge_after < moved) return -1;
    position[v] = p;
    for (size_t k = 0; k < faces[f].size(); ++k) face_of.erase({faces[f][k], faces[f][(k + 1) % faces[f].size()]});
    faces[f].clear();
    for (const auto* q : {&q1, &q2}) {
      if (q->size() < 3) continue;
      if (faces[f].empty()) {
        faces[f] = *q;
        Register(f);
      } else {
        faces.push_back(*q);
        Register(static_cast<int>(faces.size()) - 1);
      }
    }
    return v;
  }
  // Adds vertex m (at p) on the boundary edge a → b of face f and cuts the face there
  // (BestSplit): the face as [b, v1, ..., vr, a], then [m, b, v1, ..., vj] and [vj, ..., vr, a, m].
  void SplitAt(int f, int a, int b, const Eigen::Vector3d& p, const std::vector<QuadMeshVertex>& origin,
               double min_edge) {
    const int m = static_cast<int>(position.size());
    position.push_back(p);
    std::vector<int> loop = faces[f];
    std::rotate(loop.begin(), std::find(loop.begin(), loop.end(), b), loop.end());
    std::vector<int> best1, best2;
    BestSplit(loop, m, position, origin, min_edge, &best1, &best2);
    for (size_t k = 0; k < faces[f].size(); ++k) face_of.erase({faces[f][k], faces[f][(k + 1) % faces[f].size()]});
    faces[f] = best1;
    faces.push_back(best2);
    Register(f);
    Register(static_cast<int>(faces.size()) - 1);
  }
};

// Step 2's choice for a chord a – b of face f beyond tolerance (its boundary `span` on loop
// `loop`): its ends moved instead of a new vertex, or before it (then queued again), or where
// along the span the new vertex goes.
struct ChordEnds {
  const ReferenceBoundary& boundary;
  const double tolerance, max_slide, min_edge, min_turn;
  Polygons& m;
  std::vector<QuadMeshVertex>& origin;
  std::vector<bool>& pinned;
  std::vector<std::optional<ReferenceBoundary::Location>>& located;
  std::deque<std::pair<int, int>>& queue;

  // The number of ends moved (their chords queued again); if none, *at: the new vertex's arc
  // from span.from.
  int MovedInstead(int f, int a, int b, int loop, const Span& span, double* at) {
    std::vector<Eigen::Vector3d>& position = m.position;
    const double from = span.from;
    const auto requeue = [&](int end, const std::vector<QuadMeshVertex>* on_boundary) {
      if (end < int(located.size())) located[end].reset();  // located again where it now is
      m.BoundaryHalfedges(end, on_boundary, &queue);
    };
    // The new boundary vertex: at the sharp kink (SnapToSharpKinks) of the reference boundary
    // farthest from the chord if the span holds one, else halfway. A kink within `tolerance` of
    // an end adds at most `tolerance` to the chord's deviation: it counts as that end.
    // A kink closer than min_edge to an end that may move takes that end instead.
    const double kink = boundary.FarthestKink(position[a], position[b], loop, from, span.span, min_turn, tolerance);
    if (kink >= 0.0 && std::min(kink, span.span - kink) < min_edge) {
      const bool near_start = kink < span.span - kink;
      const int end = near_start == span.a_first ? a : b;
      const double start = near_start ? from : from + span.span;
      if (SlideToKink(boundary, loop, start, from + kink - start, end, min_edge, m.faces, &position, &origin,
                      &pinned)) {
        requeue(end, nullptr);
        return 1;
      }
    }
    // Without a kink the chord is cut into the fewest equal pieces that follow the boundary
    // (its first piece now, the rest when the remainder comes round the queue): halving
    // instead cut a span 0.7 h long on a small opening into 0.35 h, then 0.175 h pieces,
    // one vertex (and one triangle) more and edges below min_edge where thirds would do.
    const int pieces = PiecesNeeded(boundary, loop, from, span.span, tolerance);
    // Pieces shorter than min_edge on a cell with an even number of sides (a new vertex would
    // leave it a triangle more): the chord is shortened instead.
    if (kink < 0.0 && span.span / pieces < min_edge && m.faces[f].size() % 2 == 0) {
      if (const int end = ShortenChord(boundary, loop, span, a, b, tolerance, max_slide, min_edge, m.faces,
                                       &position, &origin, &pinned);
          end >= 0) {
        requeue(end, &origin);
        return 1;
      }
    }
    // The same on an odd cell (where the new vertex makes two quads of a pentagon): the ends
    // move apart first, so that the pieces are min_edge long, if as many pieces still do.
    const double widen = pieces * kRoomFactor * min_edge - span.span;
    if (kink < 0.0 && widen > 0.0 && m.faces[f].size() % 2 == 1 &&
        PiecesNeeded(boundary, loop, from - 0.5 * widen, span.span + widen, tolerance) == pieces) {
      const std::vector<int> moved = WidenChord(boundary, loop, span, a, b, 0.5 * widen, 0.5 * widen, max_slide,
                                                min_edge, m.faces, &position, &origin, &pinned);
      for (const int end : moved) requeue(end, nullptr);
      if (!moved.empty()) return static_cast<int>(moved.size());
    }
    *at = kink >= 0.0 ? kink : span.span / pieces;
    return 0;
  }
};

}  // namespace

int RefineBoundaryChords(const SurfaceModel& surface, double tolerance, double max_slide, double min_edge,
                         ExtractedMesh* out) {
  if (!(tolerance > 0.0)) return 0;
  const ReferenceBoundary boundary(surface);
  std::vector<QuadMeshVertex>& origin = out->origin;
  Polygons m(out->mesh);
  std::vector<Eigen::Vector3d>& position = m.position;
  std::deque<std::pair<int, int>> queue;
  m.BoundaryHalfedges(-1, &origin, &queue);
  // 1. Slide boundary vertices along the boundary (at most max_slide from where the level
  //    lines put them) to even out neighbouring chords, so that fewer vertices are needed.
  const int slid = SlideBoundaryVertices(boundary, tolerance, max_slide, min_edge, m.faces, m.face_of, &position, &origin);
  std::vector<std::optional<ReferenceBoundary::Location>> located;  // per vertex, once
  const auto locate = [&](int v) {
    if (v >= int(located.size())) located.resize(v + 1);
    if (!located[v]) located[v] = boundary.Locate(position[v]);
    return *located[v];
  };

  // 2. Split the chords that are still too far from the boundary.
  std::vector<bool> pinned(position.size());  // inserted or slid to a kink: never moved again
  for (size_t v = 0; v < position.size(); ++v) pinned[v] = origin[v].corner;
  // Sharp kinks: those that turn by more than min_turn (SnapToSharpKinks).
  const double min_turn = SharpKinkTurn(tolerance, min_edge);
  int slid_to_kinks = SnapToSharpKinks(boundary, min_turn, min_edge, m.faces, m.face_of, &position, &origin, &pinned);
  int inserted = 0, moved_onto_boundary = 0;
  const int max_insertions = 4 * static_cast<int>(position.size()) + 16;  // a guard, reached once (above)
  ChordEnds ends{boundary, tolerance, max_slide, min_edge, min_turn, m, origin, pinned, located, queue};
  while (!queue.empty() && inserted < max_insertions) {
    const auto [a, b] = queue.front();
    queue.pop_front();
    const auto found = m.face_of.find({a, b});
    if (found == m.face_of.end()) continue;
    const int f = found->second;
    const auto la = locate(a), lb = locate(b);
    const Span span = Between(boundary, la, lb);
    if (!span.ok) continue;
    // An end off the reference boundary (the only case measured: working-mesh corners CGAL
    // had moved, geometry/remesh.cc) keeps every piece of its chord that far off: splitting
    // cannot help, and did until the guard below, 268 vertices on a steep dome.
    if (la.distance > tolerance || lb.distance > tolerance) continue;
    const double from = span.from;
    if (boundary.ChordDeviation(position[a], position[b], la.loop, from, span.span) <= tolerance) continue;

    double at = 0.0;
    if (const int moved = ends.MovedInstead(f, a, b, la.loop, span, &at); moved > 0) {
      slid_to_kinks += moved;
      continue;
    }
    Eigen::Vector3d p;
    const QuadMeshVertex on_boundary = boundary.PointAt(la.loop, from + at, &p);
    if (const int v = m.MoveOntoBoundary(f, a, b, p, origin, min_edge); v >= 0) {
      origin[v] = on_boundary;
      pinned[v] = true;
      if (v < int(located.size())) located[v].reset();  // located again where it now is
      queue.push_back({a, v});
      queue.push_back({v, b});
      ++moved_onto_boundary;
      continue;
    }
    origin.push_back(on_boundary);
    pinned.push_back(true);
    const int added = static_cast<int>(position.size());
    m.SplitAt(f, a, b, p, origin, min_edge);
    queue.push_back({a, added});
    queue.push_back({added, b});
    ++inserted;
  }
  out->stats.slid_boundary_vertices += slid + slid_to_kinks;
  out->stats.moved_onto_boundary += moved_onto_boundary;
  if (inserted == 0 && slid + slid_to_kinks + moved_onto_boundary == 0) return 0;

  m.faces.erase(std::remove_if(m.faces.begin(), m.faces.end(), [](const auto& face) { return face.size() < 3; }),
                m.faces.end());  // a triangle a vertex moved onto the boundary flattened (MoveOntoBoundary)
  out->mesh = BuildPolyMesh(position, m.faces, &out->stats.rejected_faces);
  out->stats.refined_boundary_edges += inserted;
  return inserted;
}

}  // namespace pqlayout
