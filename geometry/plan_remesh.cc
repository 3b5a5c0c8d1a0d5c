#include "geometry/plan_remesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_set>
#include <utility>
#include <vector>

#include "geometry/height_field.h"
#include "geometry/planar_domain_mesher.h"
#include "geometry/reference_boundary.h"
#include "geometry/remesh.h"

namespace pqlayout {
namespace {

constexpr double kOnTriangle = -1e-12;      // barycentric coordinate at which a point is still on a triangle
constexpr double kFacesPerCell = 4.0;       // locator grid density
constexpr double kBoundarySpacing = 0.95;   // × edge_length: chords the plan mesher need not split
constexpr double kPlanEdge = 1.0;           // the plan mesher's edge bound, × edge_length
constexpr int kRemeshRounds = 3;            // CGAL isotropic remeshing rounds on the lifted plan mesh

double Cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

// The reference's triangles in the plan, bucketed in a uniform grid (compressed rows: a
// million triangles in well under a second, ~20 MB). Height(x, y) interpolates z in the triangle under
// (x, y), or on the nearest triangle if none is (a point a few millimetres outside the plan
// boundary, on a chord of a concave stretch). The caller has made sure that no two triangles
// overlap in the plan (LoopsAreSimple, PlanOrientationOfFaces).
class PlanLocator {
 public:
  explicit PlanLocator(const SurfaceModel& s) : s_(s) {
    lo_ = s.bbox_min().head<2>();
    const Eigen::Vector2d extent = (s.bbox_max().head<2>() - lo_).cwiseMax(1e-9);
    cell_ = std::sqrt(kFacesPerCell * extent.x() * extent.y() / std::max(1, s.num_faces()));
    nx_ = std::max(1, static_cast<int>(std::ceil(extent.x() / cell_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(extent.y() / cell_)));
    start_.assign(static_cast<size_t>(nx_) * ny_ + 1, 0);
    ForEachCellOfFace([&](int, int cell) { ++start_[cell + 1]; });
    for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    faces_.resize(start_.back());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    ForEachCellOfFace([&](int f, int cell) { faces_[fill[cell]++] = f; });
  }

  double Height(double x, double y) const {
    const Eigen::Vector2d p(x, y);
    const int cx = CellX(x), cy = CellY(y);
    for (int k = start_[cy * nx_ + cx]; k < start_[cy * nx_ + cx + 1]; ++k) {
      const std::array<double, 3> l = Barycentric(faces_[k], p);
      if (std::min({l[0], l[1], l[2]}) >= kOnTriangle) return Interpolate(faces_[k], l);
    }
    return NearestHeight(p, cx, cy);
  }

 private:
  int CellX(double x) const { return std::clamp(static_cast<int>((x - lo_.x()) / cell_), 0, nx_ - 1); }
  int CellY(double y) const { return std::clamp(static_cast<int>((y - lo_.y()) / cell_), 0, ny_ - 1); }
  Eigen::Vector2d Plan(int v) const { return s_.position(v).head<2>(); }

  template <typename Visit>
  void ForEachCellOfFace(Visit visit) const {
    for (int f = 0; f < s_.num_faces(); ++f) {
      const std::array<int, 3> t = s_.face_vertices(f);
      const Eigen::Vector2d a = Plan(t[0]), b = Plan(t[1]), c = Plan(t[2]);
      const Eigen::Vector2d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
      for (int cy = CellY(lo.y()); cy <= CellY(hi.y()); ++cy)
        for (int cx = CellX(lo.x()); cx <= CellX(hi.x()); ++cx) visit(f, cy * nx_ + cx);
    }
  }

  std::array<double, 3> Barycentric(int f, const Eigen::Vector2d& p) const {
    const std::array<int, 3> t = s_.face_vertices(f);
    const Eigen::Vector2d a = Plan(t[0]), b = Plan(t[1]), c = Plan(t[2]);
    const double area = Cross(b - a, c - a);
    const double l1 = Cross(p - a, c - a) / area, l2 = Cross(b - a, p - a) / area;
    return {1.0 - l1 - l2, l1, l2};
  }
  double Interpolate(int f, const std::array<double, 3>& l) const {
    const std::array<int, 3> t = s_.face_vertices(f);
    return l[0] * s_.position(t[0]).z() + l[1] * s_.position(t[1]).z() + l[2] * s_.position(t[2]).z();
  }

  // z at the closest plan point of the nearest triangle, searched ring by ring around the
  // point's cell until a ring with triangles and the ring after it are done.
  double NearestHeight(const Eigen::Vector2d& p, int cx, int cy) const {
    double best = std::numeric_limits<double>::infinity(), z = 0.0;
    int found_at = -1;
    for (int ring = 0; ring <= std::max(nx_, ny_) && (found_at < 0 || ring <= found_at + 1); ++ring) {
      for (int y = cy - ring; y <= cy + ring; ++y) {
        for (int x = cx - ring; x <= cx + ring; ++x) {
          if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
          if (std::max(std::abs(x - cx), std::abs(y - cy)) != ring) continue;
          for (int k = start_[y * nx_ + x]; k < start_[y * nx_ + x + 1]; ++k) {
            if (found_at < 0) found_at = ring;
            ClosestOnTriangle(faces_[k], p, &best, &z);
          }
        }
      }
    }
    return z;
  }
  void ClosestOnTriangle(int f, const Eigen::Vector2d& p, double* best, double* z) const {
    const std::array<int, 3> t = s_.face_vertices(f);
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d a = s_.position(t[i]), b = s_.position(t[(i + 1) % 3]);
      const Eigen::Vector2d ab = (b - a).head<2>();
      const double u = std::clamp((p - a.head<2>()).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
      const Eigen::Vector3d q = a + u * (b - a);
      const double d = (q.head<2>() - p).squaredNorm();
      if (d < *best) *best = d, *z = q.z();
    }
  }

  const SurfaceModel& s_;
  Eigen::Vector2d lo_;
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_, faces_;
};

// One boundary loop resampled through its own vertices: the corners, and between two corners
// (or once round a loop without any) the vertices nearest to equal arc-length steps no longer
// than `spacing`.
DomainLoop ResampleLoop(const SurfaceModel& s, const BoundaryLoop& loop, const std::unordered_set<int>& corners,
                        double spacing) {
  const int n = static_cast<int>(loop.vertices.size());
  std::vector<double> arc(2 * n + 1, 0.0);  // unwrapped twice round the loop
  for (int i = 1; i <= 2 * n; ++i)
    arc[i] = arc[i - 1] + (s.position(loop.vertices[i % n]) - s.position(loop.vertices[(i - 1) % n])).norm();
  std::vector<int> anchors;
  for (int i = 0; i < n; ++i)
    if (corners.count(loop.vertices[i].idx())) anchors.push_back(i);
  if (anchors.empty()) anchors.push_back(0);
  std::vector<int> kept;
  for (size_t k = 0; k < anchors.size(); ++k) {
    const int a = anchors[k];
    const int b = k + 1 < anchors.size() ? anchors[k + 1] : anchors[0] + n;
    const double span = arc[b] - arc[a];
    int pieces = std::max(1, static_cast<int>(std::ceil(span / spacing)));
    if (anchors.size() == 1) pieces = std::max(pieces, 3);
    kept.push_back(a);
    for (int j = 1; j < pieces; ++j) {
      const double target = arc[a] + j * span / pieces;
      int i = static_cast<int>(std::lower_bound(arc.begin() + a, arc.begin() + b, target) - arc.begin());
      if (i > a + 1 && target - arc[i - 1] < arc[i] - target) --i;
      if (i > kept.back() && i < b) kept.push_back(i);
    }
  }
  DomainLoop out;
  for (const int i : kept) out.polygon.push_back(s.position(loop.vertices[i % n]).head<2>());
  return out;
}

double PlanArea(const DomainLoop& loop) {
  double twice = 0.0;
  for (size_t i = 0; i < loop.polygon.size(); ++i) twice += Cross(loop.polygon[i], loop.polygon[(i + 1) % loop.polygon.size()]);
  return 0.5 * std::abs(twice);
}

// Whether two segments a–b and c–d share a point (collinear overlaps included).
bool SegmentsMeet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  const Eigen::Vector2d& d) {
  const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, d - a), d3 = Cross(d - c, a - c), d4 = Cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  const auto on = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r, double cross) {
    return cross == 0.0 && r.x() >= std::min(p.x(), q.x()) && r.x() <= std::max(p.x(), q.x()) &&
           r.y() >= std::min(p.y(), q.y()) && r.y() <= std::max(p.y(), q.y());
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

// Whether the loops, as plan polygons, are simple and pairwise disjoint: no two segments meet
// except neighbours at their shared vertex. With every face facing one way, that makes the
// reference a height field (a surface folded over the plan has a boundary that crosses itself
// in the plan); and the plan mesher's refinement need not end on a domain that overlaps itself
// (a self-overlapping ramp kept it busy for minutes). O(segments²): a few hundred at the
// working edge.
bool LoopsAreSimple(const std::vector<DomainLoop>& loops) {
  std::vector<std::array<Eigen::Vector2d, 2>> segments;
  std::vector<std::pair<int, int>> where;  // (loop, index in loop)
  for (size_t l = 0; l < loops.size(); ++l) {
    const auto& p = loops[l].polygon;
    for (size_t i = 0; i < p.size(); ++i) {
      segments.push_back({p[i], p[(i + 1) % p.size()]});
      where.emplace_back(static_cast<int>(l), static_cast<int>(i));
    }
  }
  for (size_t i = 0; i < segments.size(); ++i) {
    for (size_t j = i + 1; j < segments.size(); ++j) {
      if (where[i].first == where[j].first) {
        const int n = static_cast<int>(loops[where[i].first].polygon.size());
        const int gap = std::abs(where[i].second - where[j].second);
        if (gap == 1 || gap == n - 1) continue;  // neighbours share a vertex
      }
      if (SegmentsMeet(segments[i][0], segments[i][1], segments[j][0], segments[j][1])) return false;
    }
  }
  return true;
}

// +1 if every face's normal is within kMaxSlopeDeg of +z, -1 if of -z, 0 otherwise.
int PlanOrientationOfFaces(const SurfaceModel& s) {
  const double min_nz = std::cos(kMaxSlopeDeg * M_PI / 180.0);
  bool up = true, down = true;
  for (int f = 0; f < s.num_faces() && (up || down); ++f) {
    up &= s.face_normal(f).z() >= min_nz;
    down &= s.face_normal(f).z() <= -min_nz;
  }
  return up ? 1 : down ? -1 : 0;
}

void ReverseFaces(TriMesh* mesh) {
  TriMesh reversed;
  for (const VertexHandle v : mesh->vertices()) reversed.add_vertex(mesh->point(v));
  for (const FaceHandle f : mesh->faces()) {
    std::vector<VertexHandle> ids;
    for (const VertexHandle v : mesh->fv_range(f)) ids.push_back(v);
    reversed.add_face(ids[2], ids[1], ids[0]);
  }
  reversed.update_face_normals();
  *mesh = std::move(reversed);
}

}  // namespace

bool RemeshOverPlan(const SurfaceModel& surface, double edge_length, double corner_angle_deg, TriMesh* out,
                    std::string* why_not) {
  out->clear();
  const int orientation = PlanOrientationOfFaces(surface);
  if (orientation == 0) {
    *why_not = "a face is steeper than " + std::to_string(static_cast<int>(kMaxSlopeDeg)) + "° or faces down";
    return false;
  }
  const std::vector<int> corner_list = surface.BoundaryCorners(corner_angle_deg * M_PI / 180.0);
  const std::unordered_set<int> corners(corner_list.begin(), corner_list.end());
  HeightField field;
  for (const BoundaryLoop& loop : surface.boundary_loops())
    field.domain.push_back(ResampleLoop(surface, loop, corners, kBoundarySpacing * edge_length));
  if (field.domain.empty()) {
    *why_not = "it has no boundary";
    return false;
  }
  for (const DomainLoop& loop : field.domain) {
    if (loop.polygon.size() < 3) {
      *why_not = "a boundary loop has fewer than 3 vertices at this edge length";
      return false;
    }
  }
  if (!LoopsAreSimple(field.domain)) {
    *why_not = "its boundary crosses itself in the plan";
    return false;
  }
  // MeshPlanarDomain wants the outer loop first: the one enclosing the most plan area.
  std::iter_swap(field.domain.begin(),
                 std::max_element(field.domain.begin(), field.domain.end(),
                                  [](const DomainLoop& a, const DomainLoop& b) { return PlanArea(a) < PlanArea(b); }));
  PlanLocator locator(surface);
  field.height = [&locator](double x, double y) { return locator.Height(x, y); };
  TriMesh lifted;
  const Status meshed = MeshHeightField(field, kPlanEdge * edge_length, &lifted);
  if (!meshed.ok()) {
    *why_not = "its plan domain cannot be meshed: " + meshed.message();
    return false;
  }
  // The lifted plan mesh is Delaunay with angles ≥ 20°; CGAL's remeshing of it (~0.3 s at 12k
  // triangles) gives the near-equilateral, mostly valence-6 kind of mesh the solve had before
  // (the level sets on either kind draw from the same distribution: benchmarks/RESULTS.md,
  // 2026-12-03). Each vertex is then put back on the reference (CGAL projects onto its
  // input, here a chord surface).
  const SurfaceModel plan_model(std::move(lifted));
  const Status remeshed = RemeshIsotropic(plan_model, edge_length, corner_angle_deg, kRemeshRounds, out);
  if (!remeshed.ok()) {
    *why_not = "CGAL could not remesh its plan mesh: " + remeshed.message();
    out->clear();
    return false;
  }
  // Boundary vertices onto the reference's boundary (CGAL slid them along the plan mesh's
  // boundary chords, up to 6 cm inside the Great Court's ring at a 1.2 m edge), the others
  // onto the reference straight below or above them.
  const ReferenceBoundary boundary(surface);
  for (const VertexHandle v : out->vertices()) {
    TriMesh::Point p = out->point(v);
    if (out->is_boundary(v)) {
      Eigen::Vector3d q;
      const ReferenceBoundary::Location at = boundary.Locate(ToEigen(p));
      boundary.PointAt(at.loop, at.arc, &q);
      p = TriMesh::Point(q.x(), q.y(), q.z());
    } else {
      p[2] = locator.Height(p[0], p[1]);
    }
    out->set_point(v, p);
  }
  out->update_face_normals();
  if (orientation < 0) ReverseFaces(out);
  return true;
}

}  // namespace pqlayout
