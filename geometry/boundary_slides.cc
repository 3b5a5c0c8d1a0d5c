#include "geometry/boundary_slides.h"

#include <algorithm>
#include <tuple>
#include <cmath>
#include <set>

#include "geometry/polygon_shape.h"

namespace pqlayout::boundary_internal {
namespace {

// What a slide must not spoil at a vertex: the smallest angle of the faces at it and its
// shortest edge.
class VertexShape {
 public:
  VertexShape(const std::vector<std::vector<int>>& faces, const std::vector<Eigen::Vector3d>& position)
      : faces_(faces), position_(position), faces_at_(position.size()) {
    for (size_t f = 0; f < faces.size(); ++f)
      for (const int v : faces[f]) faces_at_[v].push_back(int(f));
  }
  double SmallestAngle(int v) const {
    double angle = M_PI;
    for (const int f : faces_at_[v]) angle = std::min(angle, ShapeAngle(position_, faces_[f]));
    return angle;
  }
  double ShortestEdge(int v) const {
    double shortest = INFINITY;
    for (const int f : faces_at_[v]) {
      const auto& face = faces_[f];
      const size_t k = std::find(face.begin(), face.end(), v) - face.begin(), m = face.size();
      for (const int w : {face[(k + 1) % m], face[(k + m - 1) % m]})
        shortest = std::min(shortest, (position_[w] - position_[v]).norm());
    }
    return shortest;
  }

 private:
  const std::vector<std::vector<int>>& faces_;
  const std::vector<Eigen::Vector3d>& position_;  // read as it changes
  std::vector<std::vector<int>> faces_at_;
};

// SlideBoundaryVertices on one mesh boundary loop (below). Returns the number of vertices moved.
int SlideLoop(const ReferenceBoundary& boundary, const std::vector<int>& loop, double tolerance, double max_slide,
              double min_edge, const VertexShape& shape, std::vector<Eigen::Vector3d>* position,
              std::vector<QuadMeshVertex>* origin) {
  const size_t n = loop.size();
  // Arc length along the walk from loop[0]; the walk must go one way round the reference loop.
  const auto l0 = boundary.Locate((*position)[loop[0]]);
  const Span first_step = Between(boundary, l0, boundary.Locate((*position)[loop[1]]));
  if (!first_step.ok) return 0;
  const bool forward = first_step.a_first;
  std::vector<double> t(n + 1, 0.0);
  bool consistent = true;
  for (size_t i = 1; i <= n && consistent; ++i) {
    const Span step = Between(boundary, boundary.Locate((*position)[loop[i - 1]]),
                              boundary.Locate((*position)[loop[i % n]]));
    consistent = step.ok && step.a_first == forward && boundary.Locate((*position)[loop[i % n]]).loop == l0.loop;
    t[i] = t[i - 1] + step.span;
  }
  if (!consistent) return 0;
  const auto arc = [&](double u) { return forward ? l0.arc + u : l0.arc - u; };
  const auto point = [&](double u) {
    Eigen::Vector3d p;
    boundary.PointAt(l0.loop, arc(u), &p);
    return p;
  };
  // Deviation of the chord u0 → u1 cut into k equal pieces.
  const auto deviation = [&](double u0, double u1, int k) {
    double d = 0.0;
    const double piece = (u1 - u0) / k;
    for (int j = 0; j < k; ++j) {
      const double a = u0 + j * piece, b = a + piece;
      d = std::max(d, boundary.ChordDeviation(point(a), point(b), l0.loop, forward ? arc(a) : arc(b), piece));
    }
    return d;
  };
  int moved = 0;
  double previous = 0.0;
  for (size_t i = 1; i < n; ++i) {
    const int v = loop[i];
    double place = t[i];
    if (!(*origin)[v].corner) {
      const double lo = std::max(t[i] - max_slide, previous + kSlideMargin * (t[i] - previous));
      const double hi = std::min(t[i] + max_slide, t[i + 1] - kSlideMargin * (t[i + 1] - t[i]));
      if (lo < hi) {
        int k = 1;
        while (k < kMaxPieces && deviation(previous, lo, k) > tolerance) ++k;
        const bool keep = k == 1 && t[i] >= lo && t[i] <= hi && deviation(previous, t[i], 1) <= tolerance;
        if (!keep) {
          double a = lo, b = hi;  // farthest place in [lo, hi] where k pieces are within tolerance
          if (deviation(previous, hi, k) <= tolerance) {
            a = hi;
          } else {
            for (int it = 0; it < 40; ++it) {
              const double mid = 0.5 * (a + b);
              (deviation(previous, mid, k) <= tolerance ? a : b) = mid;
            }
          }
          place = a;
        }
      }
    }
    if (place != t[i]) {
      const double angle_before = shape.SmallestAngle(v), edge_before = shape.ShortestEdge(v);
      const Eigen::Vector3d old_position = (*position)[v];
      Eigen::Vector3d p;
      const QuadMeshVertex slid = boundary.PointAt(l0.loop, arc(place), &p);
      (*position)[v] = p;
      if (shape.SmallestAngle(v) < std::min(angle_before, kGoodAngle) ||
          shape.ShortestEdge(v) < std::min(edge_before, min_edge)) {
        (*position)[v] = old_position;
        place = t[i];
      } else {
        (*origin)[v] = slid;
        ++moved;
      }
    }
    previous = place;
  }
  return moved;
}

}  // namespace

Span Between(const ReferenceBoundary& boundary, const ReferenceBoundary::Location& a,
             const ReferenceBoundary::Location& b) {
  Span s;
  if (a.loop < 0 || a.loop != b.loop) return s;
  const double length = boundary.length(a.loop);
  double forward = std::fmod(b.arc - a.arc, length);
  if (forward < 0.0) forward += length;
  s.a_first = forward <= length - forward;
  s.from = s.a_first ? a.arc : b.arc;
  s.span = s.a_first ? forward : length - forward;
  s.ok = s.span > 0.0 && s.span <= 0.5 * length;
  return s;
}

std::vector<std::vector<int>> MeshBoundaryLoops(const std::map<std::pair<int, int>, int>& face_of,
                                                const std::vector<QuadMeshVertex>& origin) {
  std::map<int, int> next;  // along the mesh boundary, in the faces' orientation
  for (const auto& [halfedge, f] : face_of)
    if (!face_of.count({halfedge.second, halfedge.first})) next[halfedge.first] = halfedge.second;
  std::set<int> visited;
  std::vector<std::vector<int>> loops;
  for (const auto& [first, unused] : next) {
    if (visited.count(first)) continue;
    // The loop through `first`, starting at a corner if there is one.
    std::vector<int> loop;
    for (int v = first; !visited.count(v) && next.count(v); v = next.at(v)) loop.push_back(v), visited.insert(v);
    const auto corner = std::find_if(loop.begin(), loop.end(), [&](int v) { return origin[v].corner; });
    if (corner != loop.end()) std::rotate(loop.begin(), corner, loop.end());
    loops.push_back(std::move(loop));
  }
  return loops;
}

int SlideBoundaryVertices(const ReferenceBoundary& boundary, double tolerance, double max_slide, double min_edge,
                          const std::vector<std::vector<int>>& faces,
                          const std::map<std::pair<int, int>, int>& face_of, std::vector<Eigen::Vector3d>* position,
                          std::vector<QuadMeshVertex>* origin) {
  if (!(max_slide > 0.0)) return 0;
  const VertexShape shape(faces, *position);
  int moved = 0;
  for (const auto& loop : MeshBoundaryLoops(face_of, *origin)) {
    if (loop.size() < 3) continue;
    moved += SlideLoop(boundary, loop, tolerance, max_slide, min_edge, shape, position, origin);
  }
  return moved;
}

namespace {

// SlideToKink's move with its own floor for the edges at v: none may end shorter than
// min(floor, what it had).
bool SlideAlong(const ReferenceBoundary& boundary, int loop, double arc, double move, int v, double floor,
                const std::vector<std::vector<int>>& faces, std::vector<Eigen::Vector3d>* position,
                std::vector<QuadMeshVertex>* origin, std::vector<bool>* pinned) {
  if ((*pinned)[v]) return false;
  std::vector<std::vector<int>> at_v;  // the faces at v (a linear scan: slides are few)
  for (const auto& face : faces)
    if (std::find(face.begin(), face.end(), v) != face.end()) at_v.push_back(face);
  const VertexShape shape(at_v, *position);
  const double angle_before = shape.SmallestAngle(v), edge_before = shape.ShortestEdge(v);
  const Eigen::Vector3d old_position = (*position)[v];
  Eigen::Vector3d p;
  const QuadMeshVertex slid = boundary.PointAt(loop, arc + move, &p);
  (*position)[v] = p;
  if (shape.SmallestAngle(v) < std::min(angle_before, kGoodAngle) - kKinkAngleSlack ||
      shape.ShortestEdge(v) < std::min(edge_before, floor)) {
    (*position)[v] = old_position;
    return false;
  }
  (*origin)[v] = slid;
  (*pinned)[v] = true;
  return true;
}

}  // namespace

bool SlideToKink(const ReferenceBoundary& boundary, int loop, double arc, double move, int v, double min_edge,
                 const std::vector<std::vector<int>>& faces, std::vector<Eigen::Vector3d>* position, std::vector<QuadMeshVertex>* origin,
                 std::vector<bool>* pinned) {
  return SlideAlong(boundary, loop, arc, move, v, std::min(min_edge, std::abs(move)), faces, position, origin, pinned);
}

std::vector<int> WidenChord(const ReferenceBoundary& boundary, int loop, const Span& span, int a, int b, double back,
                            double forward, double max_slide, double min_edge, const std::vector<std::vector<int>>& faces,
                            std::vector<Eigen::Vector3d>* position, std::vector<QuadMeshVertex>* origin,
                            std::vector<bool>* pinned) {
  const int first = span.a_first ? a : b, last = span.a_first ? b : a;
  // A pinned end (a corner, an inserted vertex, one slid to a kink) leaves its share to the other.
  if ((*pinned)[first]) forward += back, back = 0.0;
  if ((*pinned)[last]) back += forward, forward = 0.0;
  if ((back > 0.0 && (*pinned)[first]) || (forward > 0.0 && (*pinned)[last]) || back > max_slide || forward > max_slide)
    return {};
  const std::vector<std::tuple<int, double, double>> moves = {{first, span.from, -back}, {last, span.from + span.span, forward}};
  std::vector<int> moved;
  const std::vector<Eigen::Vector3d> old_position = *position;
  const std::vector<QuadMeshVertex> old_origin = *origin;
  for (const auto& [v, arc, move] : moves) {
    if (move == 0.0) continue;
    if (!SlideAlong(boundary, loop, arc, move, v, min_edge, faces, position, origin, pinned)) {
      for (const int w : moved) (*position)[w] = old_position[w], (*origin)[w] = old_origin[w], (*pinned)[w] = false;
      return {};
    }
    moved.push_back(v);
  }
  return moved;
}

int SnapToSharpKinks(const ReferenceBoundary& boundary, double min_turn, double min_edge,
                     const std::vector<std::vector<int>>& faces, const std::map<std::pair<int, int>, int>& face_of,
                     std::vector<Eigen::Vector3d>* position, std::vector<QuadMeshVertex>* origin,
                     std::vector<bool>* pinned) {
  int moved = 0;
  for (const auto& loop : MeshBoundaryLoops(face_of, *origin)) {
    const size_t n = loop.size();
    if (n < 3) continue;
    for (size_t i = 0; i < n; ++i) {
      const int v = loop[i];
      if ((*pinned)[v]) continue;
      const auto at = boundary.Locate((*position)[v]);
      const double kink = boundary.NearestKink(at.loop, at.arc, min_edge, min_turn);
      if (std::isnan(kink)) continue;
      if (std::abs(kink) < 1e-9 * min_edge) {  // already there: stays
        (*pinned)[v] = true;
        continue;
      }
      bool room = true;
      for (const int w : {loop[(i + 1) % n], loop[(i + n - 1) % n]}) {
        const auto there = boundary.Locate((*position)[w]);
        const double offset = std::remainder(there.arc - at.arc, boundary.length(at.loop));
        if (there.loop != at.loop || (offset * kink > 0.0 && std::abs(kink) >= 0.5 * std::abs(offset))) room = false;
      }
      if (room && SlideToKink(boundary, at.loop, at.arc, kink, v, min_edge, faces, position, origin, pinned)) ++moved;
    }
  }
  return moved;
}

int ShortenChord(const ReferenceBoundary& boundary, int loop, const Span& span, int a, int b, double tolerance,
                 double max_slide, double min_edge, const std::vector<std::vector<int>>& faces,
                 std::vector<Eigen::Vector3d>* position, std::vector<QuadMeshVertex>* origin,
                 std::vector<bool>* pinned) {
  const auto within = [&](double from, double length) {
    Eigen::Vector3d p, q;
    boundary.PointAt(loop, from, &p);
    boundary.PointAt(loop, from + length, &q);
    return boundary.ChordDeviation(p, q, loop, from, length) <= tolerance;
  };
  // The longest chord within tolerance that keeps the start (forward) or the end (backward).
  const auto longest = [&](bool keep_start) {
    double lo = 0.0, hi = span.span;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      (within(keep_start ? span.from : span.from + span.span - mid, mid) ? lo : hi) = mid;
    }
    return lo;
  };
  const int start = span.a_first ? a : b, end = span.a_first ? b : a;
  const double move_end = span.span - longest(true), move_start = span.span - longest(false);
  const std::pair<double, int> tries[2] = {{move_end, end}, {move_start, start}};
  for (int t = 0; t < 2; ++t) {
    const auto [move, v] = tries[move_start < move_end ? 1 - t : t];
    if (move > max_slide) continue;
    const bool is_end = v == end;
    const double arc = is_end ? span.from + span.span : span.from;
    if (SlideToKink(boundary, loop, arc, is_end ? -move : move, v, min_edge, faces, position, origin, pinned)) return v;
  }
  return -1;
}

}  // namespace pqlayout::boundary_internal
