// The extraction's first two steps (quad_extraction.h, "Method"): the Cutter cuts every
// reference triangle along the integer levels of φ and ψ into convex pieces labelled by their
// cell, keying every cut point symbolically; Regions joins the pieces of one label across
// shared edges (and across seams, through the label maps) and walks each region's boundary
// loops. Internal to the extraction (quad_extraction.cc); the clean-up is quad_cleanup.h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "geometry/quad_extraction.h"
#include "geometry/seams.h"
#include "geometry/surface_model.h"

namespace pqlayout::extraction_internal {

enum Family { kPhi = 0, kPsi = 1 };

// The curve a piece edge lies on: a φ line (level id), a ψ line, a reference edge (id) or,
// after normalisation of region loops, the reference boundary.
struct Carrier {
  enum Kind { kPhiLine = 0, kPsiLine = 1, kReferenceEdge = 2, kBoundary = 3 };
  int kind = kReferenceEdge;
  int id = -1;
  bool operator==(const Carrier& o) const { return kind == o.kind && id == o.id; }
  bool operator!=(const Carrier& o) const { return !(*this == o); }
};

// A point of the cut: a reference vertex, a point inside a reference edge or inside a face.
struct CutPoint {
  int vertex = -1;                      // reference vertex, or
  int edge = -1, from = -1, to = -1;    // inside edge (from, to): from + t (to − from), or
  double t = 0.0;
  int face = -1;                        // inside a face (the one it was made in)
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // in that face (origin)
  int origin_face = -1;
  double value[2] = {0.0, 0.0};         // φ, ψ, computed once per key
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  bool on_boundary = false;
  bool corner = false;
};

struct Corner {
  int point;
  Carrier carrier;  // of the edge to the next corner
};
using Polygon = std::vector<Corner>;

struct Piece {
  int label[2];  // (⌊φ⌋, ⌊ψ⌋)
  Polygon corners;
  int face;      // the reference triangle it was cut from
};

// Values within this distance of an integer snap to it (made once per key, so consistent).
constexpr double kSnap = 1e-10;
inline double Snap(double x) {
  const double r = std::round(x);
  return std::abs(x - r) <= kSnap * std::max(1.0, std::abs(x)) ? r : x;
}

class Cutter {
 public:
  // vertex_on_boundary, edge_on_boundary: per vertex / edge of `surface`, on the reference
  // boundary (seam edges of a cut surface are not).
  Cutter(const SurfaceModel& surface, const std::vector<double>& phi, const std::vector<double>& psi,
         const std::vector<int>& corners, const std::vector<char>& vertex_on_boundary,
         const std::vector<char>& edge_on_boundary)
      : surface_(surface),
        values_{&phi, &psi},
        vertex_on_boundary_(vertex_on_boundary),
        edge_on_boundary_(edge_on_boundary),
        vertex_point_(surface.num_vertices(), -1) {
    is_corner_.assign(surface.num_vertices(), 0);
    for (const int v : corners) is_corner_[v] = 1;
    const TriMesh& mesh = surface.mesh();
    face_edges_.resize(surface.num_faces());
    for (int f = 0; f < surface.num_faces(); ++f) {
      const auto ids = surface.face_vertices(f);
      for (int k = 0; k < 3; ++k)
        face_edges_[f][k] =
            mesh.edge_handle(mesh.find_halfedge(VertexHandle(ids[k]), VertexHandle(ids[(k + 1) % 3]))).idx();
    }
  }

  const std::vector<CutPoint>& points() const { return points_; }

  // All pieces of face f.
  void CutFace(int f, std::vector<Piece>* pieces) {
    const auto ids = surface_.face_vertices(f);
    Polygon triangle;
    for (int k = 0; k < 3; ++k)
      triangle.push_back({VertexPoint(ids[k], f), {Carrier::kReferenceEdge, face_edges_[f][k]}});
    for (const auto& [i, slab_phi] : Slabs(f, triangle, kPhi)) {
      for (const auto& [j, slab] : Slabs(f, slab_phi, kPsi)) pieces->push_back({{i, j}, slab, f});
    }
  }

  // The point of vertex v, or −1 if no face used it yet.
  int VertexPointId(int v) const { return vertex_point_[v]; }
  // The point where `level` of `family` crosses the inside of edge e, or −1 if none was made.
  int EdgePointId(int e, int family, int level) const {
    const auto found = point_of_key_.find(std::make_tuple(1, e, family, level));
    return found == point_of_key_.end() ? -1 : found->second;
  }

  // The reference edge both points lie on, or -1.
  int CommonEdge(int p, int q) const {
    const CutPoint& a = points_[p];
    const CutPoint& b = points_[q];
    if (a.face >= 0 || b.face >= 0) return -1;
    if (a.edge >= 0 && b.edge >= 0) return a.edge == b.edge ? a.edge : -1;
    if (a.edge >= 0) return (b.vertex == a.from || b.vertex == a.to) ? a.edge : -1;
    if (b.edge >= 0) return (a.vertex == b.from || a.vertex == b.to) ? b.edge : -1;
    const auto h = surface_.mesh().find_halfedge(VertexHandle(a.vertex), VertexHandle(b.vertex));
    return h.is_valid() ? surface_.mesh().edge_handle(h).idx() : -1;
  }

 private:
  double Value(int v, Family family) const { return (*values_[family])[v]; }

  int VertexPoint(int v, int f) {
    if (vertex_point_[v] >= 0) return vertex_point_[v];
    CutPoint p;
    p.vertex = v;
    p.value[kPhi] = Value(v, kPhi);
    p.value[kPsi] = Value(v, kPsi);
    p.position = surface_.position(v);
    p.origin_face = f;
    const auto ids = surface_.face_vertices(f);
    for (int k = 0; k < 3; ++k) p.barycentric[k] = ids[k] == v ? 1.0 : 0.0;
    p.on_boundary = vertex_on_boundary_[v];
    p.corner = is_corner_[v];
    vertex_point_[v] = static_cast<int>(points_.size());
    points_.push_back(p);
    return vertex_point_[v];
  }

  // Bit k set: the point lies on local edge k (vertices k, k+1) of face f.
  int EdgeMask(int point, int f) const {
    const CutPoint& p = points_[point];
    if (p.face >= 0) return 0;
    const auto ids = surface_.face_vertices(f);
    int mask = 0;
    for (int k = 0; k < 3; ++k) {
      if (p.vertex >= 0 && (ids[k] == p.vertex || ids[(k + 1) % 3] == p.vertex)) mask |= 1 << k;
      if (p.edge >= 0 && face_edges_[f][k] == p.edge) mask |= 1 << k;
    }
    return mask;
  }

  Eigen::Vector3d LocalBarycentric(int point, int f) const {
    const CutPoint& p = points_[point];
    if (p.face >= 0) return p.barycentric;  // face points are only used in their face
    const auto ids = surface_.face_vertices(f);
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      if (ids[k] == p.vertex) b[k] = 1.0;
      if (ids[k] == p.from) b[k] = 1.0 - p.t;
      if (ids[k] == p.to) b[k] = p.t;
    }
    return b;
  }

  // Where level `level` of `family` crosses the segment p–q of face f (one end below, the
  // other not); `carrier` is the curve the segment lies on.
  int Crossing(int f, int p, int q, Family family, int level, const Carrier& carrier) {
    int lower = p, upper = q;
    if (!(points_[lower].value[family] < level)) std::swap(lower, upper);
    if (points_[upper].value[family] == level) return upper;  // tie: the upper end itself
    const int common = EdgeMask(p, f) & EdgeMask(q, f);
    if (common) {
      const int k = common & 1 ? 0 : (common & 2 ? 1 : 2);
      return EdgePoint(f, k, family, level);
    }
    const Family other = family == kPhi ? kPsi : kPhi;
    if (carrier.kind != static_cast<int>(other)) return upper;  // cannot happen for valid input
    const int i = family == kPhi ? level : carrier.id, j = family == kPhi ? carrier.id : level;
    const auto key = std::make_tuple(2, f, i, j);
    const auto found = point_of_key_.find(key);
    if (found != point_of_key_.end()) return found->second;
    const double t = (level - points_[lower].value[family]) /
                     (points_[upper].value[family] - points_[lower].value[family]);
    CutPoint x;
    x.face = x.origin_face = f;
    const Eigen::Vector3d bl = LocalBarycentric(lower, f), bu = LocalBarycentric(upper, f);
    x.barycentric = bl + t * (bu - bl);
    x.value[kPhi] = i;
    x.value[kPsi] = j;
    x.position = Position(f, x.barycentric);
    return Add(key, x);
  }

  // The crossing of `level` with local edge k of face f (strictly inside the edge).
  int EdgePoint(int f, int k, Family family, int level) {
    const int e = face_edges_[f][k];
    const auto key = std::make_tuple(1, e, static_cast<int>(family), level);
    const auto found = point_of_key_.find(key);
    if (found != point_of_key_.end()) return found->second;
    const auto ids = surface_.face_vertices(f);
    int a = ids[k], b = ids[(k + 1) % 3];
    if (!(Value(a, family) < level)) std::swap(a, b);  // from the lower to the upper end
    CutPoint x;
    x.edge = e;
    x.from = a;
    x.to = b;
    x.t = (level - Value(a, family)) / (Value(b, family) - Value(a, family));
    const Family other = family == kPhi ? kPsi : kPhi;
    x.value[family] = level;
    x.value[other] = Snap(Value(a, other) + x.t * (Value(b, other) - Value(a, other)));
    x.position = surface_.position(a) + x.t * (surface_.position(b) - surface_.position(a));
    x.origin_face = f;
    x.barycentric[k] = ids[k] == a ? 1.0 - x.t : x.t;
    x.barycentric[(k + 1) % 3] = ids[k] == a ? x.t : 1.0 - x.t;
    x.on_boundary = edge_on_boundary_[e];
    return Add(key, x);
  }

  int Add(const std::tuple<int, int, int, int>& key, const CutPoint& point) {
    const int id = static_cast<int>(points_.size());
    points_.push_back(point);
    point_of_key_.emplace(key, id);
    return id;
  }

  Eigen::Vector3d Position(int f, const Eigen::Vector3d& b) const {
    const auto ids = surface_.face_vertices(f);
    return b[0] * surface_.position(ids[0]) + b[1] * surface_.position(ids[1]) + b[2] * surface_.position(ids[2]);
  }

  // Sutherland–Hodgman: the part of `polygon` with value ≥ level (keep_above) or < level.
  Polygon Clip(int f, const Polygon& polygon, Family family, int level, bool keep_above) {
    const auto inside = [&](int point) { return (points_[point].value[family] < level) != keep_above; };
    const Carrier cut{static_cast<int>(family), level};
    Polygon result;
    const size_t n = polygon.size();
    for (size_t k = 0; k < n; ++k) {
      const Corner& p = polygon[k];
      const Corner& q = polygon[(k + 1) % n];
      const bool p_in = inside(p.point), q_in = inside(q.point);
      if (p_in) {
        result.push_back(p);
        if (!q_in) result.push_back({Crossing(f, p.point, q.point, family, level, p.carrier), cut});
      } else if (q_in) {
        result.push_back({Crossing(f, p.point, q.point, family, level, p.carrier), p.carrier});
      }
    }
    return WithoutRepeats(result);
  }

  // Consecutive equal points (a crossing exactly at a corner) kept once, with the carrier of
  // the edge that leaves them.
  static Polygon WithoutRepeats(const Polygon& polygon) {
    Polygon result;
    for (const Corner& c : polygon) {
      if (!result.empty() && result.back().point == c.point) result.back() = c;
      else result.push_back(c);
    }
    while (result.size() > 1 && result.back().point == result.front().point) {
      result.pop_back();
    }
    return result;
  }

  bool IsPlateau(int f, Family family) const {
    const auto ids = surface_.face_vertices(f);
    return Value(ids[0], family) == Value(ids[1], family) && Value(ids[1], family) == Value(ids[2], family);
  }

  // The non-degenerate pieces of `polygon` between consecutive integer levels of `family`.
  std::vector<std::pair<int, Polygon>> Slabs(int f, const Polygon& polygon, Family family) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Corner& c : polygon) {
      lo = std::min(lo, points_[c.point].value[family]);
      hi = std::max(hi, points_[c.point].value[family]);
    }
    std::vector<std::pair<int, Polygon>> slabs;
    for (int level = static_cast<int>(std::floor(lo)); level <= static_cast<int>(std::floor(hi)); ++level) {
      Polygon slab = Clip(f, Clip(f, polygon, family, level, true), family, level + 1, false);
      if (slab.size() < 3) continue;
      // All corners exactly on the lower level: a zero-area sliver along a ridge at the
      // level, unless the whole face is at the level (a plateau, which belongs to the slab).
      const bool sliver = !IsPlateau(f, family) &&
                          std::all_of(slab.begin(), slab.end(),
                                      [&](const Corner& c) { return points_[c.point].value[family] == level; });
      if (!sliver) slabs.emplace_back(level, std::move(slab));
    }
    return slabs;
  }

  const SurfaceModel& surface_;
  const std::vector<double>* values_[2];
  const std::vector<char>& vertex_on_boundary_;
  const std::vector<char>& edge_on_boundary_;
  std::vector<char> is_corner_;
  std::vector<std::array<int, 3>> face_edges_;
  std::vector<int> vertex_point_;
  std::map<std::tuple<int, int, int, int>, int> point_of_key_;
  std::vector<CutPoint> points_;
};

// ---- Regions: pieces of one label joined across shared edges ------------------------------

struct PieceEdge {
  int piece, k;  // edge from corner k to k + 1 of piece
};

// The label a cell has on the other side of a seam edge: u₊ = sign·u₋ + offset, so a piece
// strictly between levels i and i + 1 on the minus side lies between sign·i + offset and
// sign·(i + 1) + offset on the plus side.
struct LabelMap {
  int sign = 1;
  int offset[2] = {0, 0};
  bool forward = true;  // minus → plus (else plus → minus)
  std::array<int, 2> Apply(const int label[2]) const {
    std::array<int, 2> mapped{};
    for (int family = 0; family < 2; ++family)
      mapped[family] = sign < 0 ? offset[family] - label[family] - 1
                                : label[family] + (forward ? offset[family] : -offset[family]);
    return mapped;
  }
};
// (face, face across a seam edge) → the map of labels from the first to the second.
using SeamLabelMaps = std::map<std::pair<int, int>, LabelMap>;

class Regions {
 public:
  // canonical: per cut point, the point it stands for (points on the two sides of a seam are
  // one point); across: label maps between faces on the two sides of a seam edge.
  Regions(const std::vector<Piece>& pieces, const std::vector<int>& canonical, const SeamLabelMaps& across)
      : pieces_(pieces), canonical_(canonical), across_(across), parent_(pieces.size()) {
    std::iota(parent_.begin(), parent_.end(), 0);
    for (size_t p = 0; p < pieces.size(); ++p) {
      const Polygon& c = pieces[p].corners;
      for (size_t k = 0; k < c.size(); ++k)
        edge_of_.emplace(Key(c[k].point, c[(k + 1) % c.size()].point), PieceEdge{int(p), int(k)});
    }
    for (size_t p = 0; p < pieces.size(); ++p) {
      const Polygon& c = pieces[p].corners;
      for (size_t k = 0; k < c.size(); ++k) {
        const PieceEdge* twin = Twin({int(p), int(k)});
        if (twin) Union(int(p), twin->piece);
      }
    }
  }

  int From(PieceEdge e) const { return pieces_[e.piece].corners[e.k].point; }
  int To(PieceEdge e) const {
    const Polygon& c = pieces_[e.piece].corners;
    return c[(e.k + 1) % c.size()].point;
  }
  const Carrier& PieceCarrier(PieceEdge e) const { return pieces_[e.piece].corners[e.k].carrier; }

  // The opposite edge in a piece of the same cell (the same label, or across a seam the
  // corresponding one), or null.
  const PieceEdge* Twin(PieceEdge e) const {
    const auto it = edge_of_.find(Key(To(e), From(e)));
    if (it == edge_of_.end()) return nullptr;
    const Piece& a = pieces_[e.piece];
    const Piece& b = pieces_[it->second.piece];
    std::array<int, 2> label{a.label[0], a.label[1]};
    if (a.face != b.face && !across_.empty()) {
      const auto map = across_.find({a.face, b.face});
      if (map != across_.end()) label = map->second.Apply(a.label);
    }
    if (label[0] != b.label[0] || label[1] != b.label[1]) return nullptr;
    return &it->second;
  }

  // The region boundary edge after e: turn around To(e) through pieces of the same label.
  PieceEdge NextOnBoundary(PieceEdge e) const {
    PieceEdge next = Following(e);
    for (size_t guard = 0; guard < pieces_.size(); ++guard) {
      const PieceEdge* twin = Twin(next);
      if (!twin) return next;
      next = Following(*twin);
    }
    return next;
  }

  int Find(int p) {
    while (parent_[p] != p) p = parent_[p] = parent_[parent_[p]];
    return p;
  }

  // The boundary loops of every region (region = root piece).
  std::map<int, std::vector<std::vector<PieceEdge>>> Loops() {
    std::set<std::pair<int, int>> visited;
    std::map<int, std::vector<std::vector<PieceEdge>>> loops;
    for (size_t p = 0; p < pieces_.size(); ++p) {
      for (size_t k = 0; k < pieces_[p].corners.size(); ++k) {
        PieceEdge start{int(p), int(k)};
        if (Twin(start) || visited.count({start.piece, start.k})) continue;
        std::vector<PieceEdge> loop;
        PieceEdge e = start;
        do {
          visited.insert({e.piece, e.k});
          loop.push_back(e);
          e = NextOnBoundary(e);
        } while (!(e.piece == start.piece && e.k == start.k) && loop.size() <= 4 * edge_of_.size());
        loops[Find(int(p))].push_back(std::move(loop));
      }
    }
    return loops;
  }

 private:
  std::pair<int, int> Key(int a, int b) const { return {canonical_[a], canonical_[b]}; }
  PieceEdge Following(PieceEdge e) const {
    return {e.piece, int((e.k + 1) % pieces_[e.piece].corners.size())};
  }
  void Union(int a, int b) { parent_[Find(a)] = Find(b); }

  const std::vector<Piece>& pieces_;
  const std::vector<int>& canonical_;
  const SeamLabelMaps& across_;
  std::vector<int> parent_;
  std::map<std::pair<int, int>, PieceEdge> edge_of_;
};

}  // namespace pqlayout::extraction_internal
