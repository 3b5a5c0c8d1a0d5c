#include "geometry/reference_boundary.h"

#include <algorithm>
#include <cmath>

namespace pqlayout {
namespace {

double PointSegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            double* t_out = nullptr) {
  const Eigen::Vector3d d = b - a;
  const double length_sq = d.squaredNorm();
  const double t = length_sq > 0.0 ? std::clamp((p - a).dot(d) / length_sq, 0.0, 1.0) : 0.0;
  if (t_out) *t_out = t;
  return (a + t * d - p).norm();
}

constexpr int kChordSamples = 8;  // segments a chord is sampled in

}  // namespace

ReferenceBoundary::ReferenceBoundary(const SurfaceModel& surface) : surface_(surface) {
  for (const auto& loop : surface.boundary_loops()) {
    Loop l;
    l.arc.push_back(0.0);
    const size_t n = loop.vertices.size();
    for (size_t k = 0; k < n; ++k) {
      l.vertices.push_back(loop.vertices[k].idx());
      l.arc.push_back(l.arc.back() +
                      (surface.position(loop.vertices[(k + 1) % n]) - surface.position(loop.vertices[k])).norm());
    }
    for (size_t k = 0; k < n; ++k) {
      const Eigen::Vector3d before = surface.position(loop.vertices[k]) - surface.position(loop.vertices[(k + n - 1) % n]);
      const Eigen::Vector3d after = surface.position(loop.vertices[(k + 1) % n]) - surface.position(loop.vertices[k]);
      l.turn.push_back(std::atan2(before.cross(after).norm(), before.dot(after)));
    }
    loops_.push_back(std::move(l));
  }
}

double ReferenceBoundary::NearestKink(int loop, double arc, double reach, double min_turn) const {
  const Loop& l = loops_[loop];
  const double length = l.arc.back();
  double best = NAN;
  for (size_t k = 0; k < l.vertices.size(); ++k) {
    if (!(l.turn[k] > min_turn)) continue;
    double offset = std::remainder(l.arc[k] - arc, length);  // in [-length/2, length/2]
    if (std::abs(offset) <= reach && !(std::abs(offset) >= std::abs(best))) best = offset;
  }
  return best;
}

double ReferenceBoundary::TurnAt(const Eigen::Vector3d& p, double within) const {
  for (const Loop& l : loops_)
    for (size_t k = 0; k < l.vertices.size(); ++k)
      if ((surface_.position(l.vertices[k]) - p).norm() <= within) return l.turn[k];
  return 0.0;
}

double SharpKinkTurn(double tolerance, double min_edge) {
  return min_edge > tolerance ? 2.0 * std::asin(tolerance / min_edge) : INFINITY;
}

ReferenceBoundary::Location ReferenceBoundary::Locate(const Eigen::Vector3d& p) const {
  Location best;
  best.distance = INFINITY;
  for (size_t l = 0; l < loops_.size(); ++l) {
    const Loop& loop = loops_[l];
    const size_t n = loop.vertices.size();
    for (size_t k = 0; k < n; ++k) {
      double t = 0.0;
      const double d = PointSegmentDistance(p, surface_.position(loop.vertices[k]),
                                            surface_.position(loop.vertices[(k + 1) % n]), &t);
      if (d < best.distance) best = {int(l), loop.arc[k] + t * (loop.arc[k + 1] - loop.arc[k]), d};
    }
  }
  return best;
}

Eigen::Vector3d ReferenceBoundary::Position(int loop, double arc, int* segment, double* t) const {
  const Loop& l = loops_[loop];
  const double length = l.arc.back();
  arc = std::fmod(arc, length);
  if (arc < 0.0) arc += length;
  const size_t n = l.vertices.size();
  size_t k = std::upper_bound(l.arc.begin(), l.arc.end(), arc) - l.arc.begin();
  k = std::min(std::max<size_t>(k, 1), n) - 1;
  const double piece = l.arc[k + 1] - l.arc[k];
  *segment = int(k);
  *t = piece > 0.0 ? std::clamp((arc - l.arc[k]) / piece, 0.0, 1.0) : 0.0;
  return (1.0 - *t) * surface_.position(l.vertices[k]) + *t * surface_.position(l.vertices[(k + 1) % n]);
}

QuadMeshVertex ReferenceBoundary::PointAt(int loop, double arc, Eigen::Vector3d* position) const {
  int k = 0;
  double t = 0.0;
  *position = Position(loop, arc, &k, &t);
  const Loop& l = loops_[loop];
  const int u = l.vertices[k], w = l.vertices[(k + 1) % l.vertices.size()];
  const TriMesh& mesh = surface_.mesh();
  auto halfedge = mesh.find_halfedge(VertexHandle(u), VertexHandle(w));
  if (!halfedge.is_valid() || mesh.is_boundary(halfedge)) halfedge = mesh.opposite_halfedge_handle(halfedge);
  QuadMeshVertex origin;
  origin.face = mesh.face_handle(halfedge).idx();
  origin.on_boundary = true;
  const auto ids = surface_.face_vertices(origin.face);
  for (int c = 0; c < 3; ++c) origin.barycentric[c] = ids[c] == u ? 1.0 - t : ids[c] == w ? t : 0.0;
  return origin;
}

std::vector<std::pair<double, int>> ReferenceBoundary::VerticesInside(int loop, double from, double span) const {
  const Loop& l = loops_[loop];
  const size_t n = l.vertices.size();
  int k = 0;
  double t = 0.0;
  Position(loop, from, &k, &t);
  const double length = l.arc.back();
  std::vector<std::pair<double, int>> inside;
  for (size_t step = 1; step <= n; ++step) {
    const size_t v = (k + step) % n;
    double ahead = l.arc[v] - std::fmod(from, length);
    if (ahead <= 0.0) ahead += length;
    if (ahead >= span) break;
    inside.push_back({ahead, int(v)});
  }
  return inside;
}

double ReferenceBoundary::ChordDeviation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int loop, double from,
                                         double span) const {
  // The span as a polyline: its ends and the loop vertices strictly inside it.
  std::vector<Eigen::Vector3d> polyline;
  int k = 0;
  double t = 0.0;
  polyline.push_back(Position(loop, from, &k, &t));
  for (const auto& [ahead, k] : VerticesInside(loop, from, span))
    polyline.push_back(surface_.position(loops_[loop].vertices[k]));
  polyline.push_back(Position(loop, from + span, &k, &t));
  double deviation = 0.0;
  for (const auto& p : polyline) deviation = std::max(deviation, PointSegmentDistance(p, a, b));
  for (int s = 0; s <= kChordSamples; ++s) {
    const Eigen::Vector3d p = a + (b - a) * (double(s) / kChordSamples);
    double d = INFINITY;
    for (size_t i = 0; i + 1 < polyline.size(); ++i) d = std::min(d, PointSegmentDistance(p, polyline[i], polyline[i + 1]));
    deviation = std::max(deviation, d);
  }
  return deviation;
}

double ReferenceBoundary::FarthestKink(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int loop, double from,
                                       double span, double min_turn, double margin) const {
  double offset = -1.0, farthest = -1.0;
  const Loop& l = loops_[loop];
  for (const auto& [ahead, k] : VerticesInside(loop, from, span)) {
    if (!(l.turn[k] > min_turn) || ahead <= margin || ahead >= span - margin) continue;
    const double d = PointSegmentDistance(surface_.position(l.vertices[k]), a, b);
    if (d > farthest) farthest = d, offset = ahead;
  }
  return offset;
}

}  // namespace pqlayout
