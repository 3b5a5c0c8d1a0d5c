// MeshPlanarDomain: CGAL constrained Delaunay refinement of a polygonal domain with holes.
// Each loop segment is pre-split at about edge_length and inserted as one polyline
// constraint, so that after refinement the vertices on every input segment can be listed
// (Constrained_triangulation_plus_2) and snapped onto their exact line or circle.
#include "geometry/planar_domain_mesher.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace pqlayout {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_triangulation_plus_2<
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Point = Cdt::Point;
using CdtFace = Cdt::Face_handle;
using CdtVertex = Cdt::Vertex_handle;

// Shape bound of Delaunay_mesh_criteria_2: sin²(minimum angle) >= 0.125, i.e. about 20.7°,
// the largest bound for which Delaunay refinement is guaranteed to terminate.
constexpr double kShapeBound = 0.125;
constexpr double kMaxTriangles = 2.0e7;
// Triangles per (domain area / edge_length²) that the size criterion produces (measured).
constexpr double kTrianglesPerSquareEdge = 5.0;
// Above this many expected triangles the interior is first seeded with a triangular lattice
// (SeedLattice): CGAL's refinement inserts its points one by one through a queue of bad
// faces, 10.6 s for the 968k-triangle Great Court plan, of which the lattice leaves only the
// band along the boundary. Below it (every default reference, every corpus roof, every working
// mesh) the mesh is the refinement's alone, as before.
constexpr double kLatticeAbove = 2.0e5;
// Lattice spacing × edge_length: under the size bound (the longest edge ≤ edge_length), and
// near the refinement's own mean edge (0.72 × edge_length on the Great Court).
constexpr double kLatticeSpacing = 0.68;
// No lattice point nearer a boundary vertex than this × edge_length: boundary pieces are at
// most edge_length long, so every point stays ≥ 0.87 edge_length from every constraint and the
// refinement meshes the band between them (at 0.75 the band's triangles along the Great
// Court's steep north edge came out at 18.3° in space after lifting, against 23.2° from the
// refinement alone; at 1.0, 23.6°).
constexpr double kLatticeClearance = 1.0;
static_assert(kLatticeClearance <= 1.0, "SeedLattice searches the 3 × 3 buckets of one edge_length round a point");

// The polyline constraint holding the pre-split pieces of one loop segment, which is named by
// its loop and the index of its first polygon vertex.
struct LoopSegment {
  Cdt::Constraint_id constraint;
  int loop = 0;
  int segment = 0;
};

double SignedArea(const std::vector<Eigen::Vector2d>& polygon) {
  double twice_area = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    twice_area += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice_area;
}

double DomainArea(const std::vector<DomainLoop>& loops) {
  double area = std::abs(SignedArea(loops[0].polygon));
  for (size_t i = 1; i < loops.size(); ++i) area -= std::abs(SignedArea(loops[i].polygon));
  return area;
}

// About how many triangles the size criterion gives the domain.
double ExpectedTriangles(const std::vector<DomainLoop>& loops, double edge_length) {
  return kTrianglesPerSquareEdge * DomainArea(loops) / (edge_length * edge_length);
}

Status ValidateLoops(const std::vector<DomainLoop>& loops, double edge_length) {
  if (!std::isfinite(edge_length) || edge_length <= 0.0) {
    return Status::InvalidInput("edge_length must be positive and finite, got " +
                                std::to_string(edge_length));
  }
  if (loops.empty()) return Status::InvalidInput("planar domain has no boundary loop");
  for (size_t i = 0; i < loops.size(); ++i) {
    const DomainLoop& loop = loops[i];
    if (loop.polygon.size() < 3) {
      return Status::InvalidInput("loop " + std::to_string(i) + " has " +
                                  std::to_string(loop.polygon.size()) +
                                  " points, a closed loop needs at least 3");
    }
    for (size_t j = 0; j < loop.polygon.size(); ++j) {
      const Eigen::Vector2d& p = loop.polygon[j];
      if (!p.allFinite()) {
        return Status::InvalidInput("loop " + std::to_string(i) + " has a non-finite point");
      }
      if (p == loop.polygon[(j + 1) % loop.polygon.size()]) {
        return Status::InvalidInput("loop " + std::to_string(i) + " repeats point " +
                                    std::to_string(j) + " (a loop is closed implicitly)");
      }
    }
    if (loop.is_circle && !(std::isfinite(loop.radius) && loop.radius > 0.0)) {
      return Status::InvalidInput("circle loop " + std::to_string(i) +
                                  " needs a positive finite radius");
    }
  }
  const double expected_triangles = ExpectedTriangles(loops, edge_length);
  if (expected_triangles > kMaxTriangles) {
    // Formatted as a double: the count can exceed any integer type (or be inf).
    std::ostringstream message;
    message.precision(3);
    message << "edge_length " << edge_length << " would give about " << expected_triangles
            << " triangles, more than the limit of 20 million";
    return Status::InvalidInput(message.str());
  }
  return Status::Ok();
}

// The segment p -> q split into equal pieces no longer than edge_length. The ends are p and
// q themselves (so that neighbouring segments share them bitwise); the split points are
// p + t (q - p), which reproduces a coordinate shared by p and q bitwise.
std::vector<Point> PreSplitSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                   double edge_length) {
  const int pieces = std::max(1, static_cast<int>(std::ceil((q - p).norm() / edge_length)));
  std::vector<Point> points{{p.x(), p.y()}};
  for (int k = 1; k < pieces; ++k) {
    const Eigen::Vector2d s = p + (static_cast<double>(k) / pieces) * (q - p);
    points.emplace_back(s.x(), s.y());
  }
  points.emplace_back(q.x(), q.y());
  return points;
}

std::vector<LoopSegment> InsertLoopConstraints(const std::vector<DomainLoop>& loops,
                                               double edge_length, Cdt* cdt) {
  std::vector<LoopSegment> segments;
  for (size_t i = 0; i < loops.size(); ++i) {
    const std::vector<Eigen::Vector2d>& polygon = loops[i].polygon;
    for (size_t j = 0; j < polygon.size(); ++j) {
      const std::vector<Point> pieces =
          PreSplitSegment(polygon[j], polygon[(j + 1) % polygon.size()], edge_length);
      segments.push_back({cdt->insert_constraint(pieces.begin(), pieces.end()), static_cast<int>(i),
                          static_cast<int>(j)});
    }
  }
  return segments;
}

// The faces flooded by nesting level (0 = outside, 1 = the domain, 2 = a hole, ...): crossing
// a constrained edge raises the level by one. first_faces: the first face of each component.
std::unordered_map<CdtFace, int> NestingLevels(const Cdt& cdt, std::vector<CdtFace>* first_faces) {
  std::unordered_map<CdtFace, int> nesting_level;
  std::deque<std::pair<CdtFace, int>> components{{cdt.infinite_face(), 0}};
  while (!components.empty()) {
    const auto [start, level] = components.front();
    components.pop_front();
    if (nesting_level.count(start)) continue;
    nesting_level[start] = level;
    first_faces->push_back(start);
    std::vector<CdtFace> stack{start};
    while (!stack.empty()) {
      const CdtFace face = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const CdtFace neighbor = face->neighbor(i);
        if (nesting_level.count(neighbor)) continue;
        if (cdt.is_constrained({face, i})) {
          components.emplace_back(neighbor, level + 1);
        } else {
          nesting_level[neighbor] = level;
          stack.push_back(neighbor);
        }
      }
    }
  }
  return nesting_level;
}

// One point inside each hole (an even nesting level above 0): the centroid of its first face.
std::vector<Point> HoleSeeds(const Cdt& cdt, const std::unordered_map<CdtFace, int>& nesting_level,
                             const std::vector<CdtFace>& first_faces) {
  std::vector<Point> seeds;
  for (const CdtFace face : first_faces) {
    const int level = nesting_level.at(face);
    if (level > 0 && level % 2 == 0) seeds.push_back(CGAL::centroid(cdt.triangle(face)));
  }
  return seeds;
}

// A triangular lattice of spacing kLatticeSpacing × edge_length over the domain's interior,
// kept kLatticeClearance × edge_length from every boundary vertex, inserted before the
// refinement (see kLatticeAbove). Call with only the loop constraints in cdt, and their
// NestingLevels.
void SeedLattice(const std::vector<DomainLoop>& loops, double edge_length,
                 const std::unordered_map<CdtFace, int>& nesting_level, Cdt* cdt) {
  // The boundary vertices bucketed by cells one edge_length wide.
  const double cell = edge_length, clearance = kLatticeClearance * edge_length;
  const auto key = [cell](double x, double y) {
    return std::make_pair(static_cast<long long>(std::floor(x / cell)), static_cast<long long>(std::floor(y / cell)));
  };
  struct PairHash {
    size_t operator()(const std::pair<long long, long long>& k) const { return std::hash<long long>()(k.first * 73856093LL ^ k.second); }
  };
  std::unordered_map<std::pair<long long, long long>, std::vector<Eigen::Vector2d>, PairHash> buckets;
  for (const CdtVertex v : cdt->finite_vertex_handles())
    buckets[key(v->point().x(), v->point().y())].emplace_back(v->point().x(), v->point().y());
  const auto clear = [&](const Eigen::Vector2d& q) {
    const auto [i, j] = key(q.x(), q.y());
    for (long long di = -1; di <= 1; ++di)
      for (long long dj = -1; dj <= 1; ++dj) {
        const auto it = buckets.find({i + di, j + dj});
        if (it == buckets.end()) continue;
        for (const Eigen::Vector2d& b : it->second)
          if ((b - q).squaredNorm() < clearance * clearance) return false;
      }
    return true;
  };
  Eigen::Vector2d lo = loops[0].polygon[0], hi = lo;
  for (const Eigen::Vector2d& p : loops[0].polygon) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double step = kLatticeSpacing * edge_length, row = step * std::sqrt(3.0) / 2.0;
  std::vector<Point> lattice;
  CdtFace hint;
  for (int j = 0; lo.y() + j * row < hi.y(); ++j)
    for (int i = 0; lo.x() + (i + 0.5 * (j % 2)) * step < hi.x(); ++i) {
      const Eigen::Vector2d q(lo.x() + (i + 0.5 * (j % 2)) * step, lo.y() + j * row);
      if (!clear(q)) continue;
      hint = cdt->locate(Point(q.x(), q.y()), hint);
      const auto level = nesting_level.find(hint);
      if (level != nesting_level.end() && level->second % 2 == 1) lattice.emplace_back(q.x(), q.y());
    }
  cdt->insert(lattice.begin(), lattice.end());
}

void RefineDomain(const std::vector<Point>& seeds, double edge_length, Cdt* cdt) {
  const Criteria criteria(kShapeBound, edge_length);
  CGAL::refine_Delaunay_mesh_2(*cdt, seeds.begin(), seeds.end(), criteria, false);
}

// The in-domain triangles with compact vertex indices; fills vertex_index for the vertices used.
void ExtractDomain(const Cdt& cdt, std::unordered_map<CdtVertex, int>* vertex_index,
                   PlanarTriangulation* out) {
  out->points.clear();
  out->triangles.clear();
  for (CdtFace face : cdt.finite_face_handles()) {
    if (!face->is_in_domain()) continue;
    std::array<int, 3> triangle;
    for (int k = 0; k < 3; ++k) {
      const CdtVertex v = face->vertex(k);
      const auto [it, inserted] = vertex_index->emplace(v, static_cast<int>(out->points.size()));
      if (inserted) out->points.emplace_back(v->point().x(), v->point().y());
      triangle[k] = it->second;
    }
    out->triangles.push_back(triangle);
  }
}

// Moves a point found on the given loop segment exactly onto it: onto the circle of a circle
// loop, onto the line x = const or y = const of an axis-parallel straight segment.
Eigen::Vector2d SnapToSegment(const DomainLoop& loop, int segment, const Eigen::Vector2d& p) {
  if (loop.is_circle) return loop.center + loop.radius * (p - loop.center).normalized();
  const Eigen::Vector2d& a = loop.polygon[segment];
  const Eigen::Vector2d& b = loop.polygon[(segment + 1) % loop.polygon.size()];
  Eigen::Vector2d snapped = p;
  if (a.x() == b.x()) snapped.x() = a.x();
  if (a.y() == b.y()) snapped.y() = a.y();
  return snapped;
}

void SnapBoundaryPoints(const Cdt& cdt, const std::vector<DomainLoop>& loops,
                        const std::vector<LoopSegment>& segments,
                        const std::unordered_map<CdtVertex, int>& vertex_index,
                        PlanarTriangulation* out) {
  for (const LoopSegment& s : segments) {
    for (CdtVertex v : cdt.vertices_in_constraint(s.constraint)) {
      const auto it = vertex_index.find(v);
      if (it == vertex_index.end()) continue;
      Eigen::Vector2d& p = out->points[it->second];
      p = SnapToSegment(loops[s.loop], s.segment, p);
    }
  }
}

}  // namespace

Status MeshPlanarDomain(const std::vector<DomainLoop>& loops, double edge_length,
                        PlanarTriangulation* out) {
  PQ_RETURN_IF_ERROR(ValidateLoops(loops, edge_length));
  Cdt cdt;
  const std::vector<LoopSegment> segments = InsertLoopConstraints(loops, edge_length, &cdt);
  std::vector<CdtFace> first_faces;
  const std::unordered_map<CdtFace, int> nesting_level = NestingLevels(cdt, &first_faces);
  const std::vector<Point> seeds = HoleSeeds(cdt, nesting_level, first_faces);
  if (ExpectedTriangles(loops, edge_length) > kLatticeAbove) SeedLattice(loops, edge_length, nesting_level, &cdt);
  RefineDomain(seeds, edge_length, &cdt);
  std::unordered_map<CdtVertex, int> vertex_index;
  ExtractDomain(cdt, &vertex_index, out);
  if (out->triangles.empty()) {
    return Status::InvalidInput("planar domain encloses no area");
  }
  SnapBoundaryPoints(cdt, loops, segments, vertex_index, out);
  return Status::Ok();
}

DomainLoop CircleLoop(const Eigen::Vector2d& center, double radius, double edge_length) {
  // A chord 2 r sin(π/n) is shorter than the arc 2πr/n <= edge_length. Arguments without a
  // sensible count give a triangle, which MeshPlanarDomain refuses (radius or edge_length).
  const double segments = std::ceil(2.0 * M_PI * radius / edge_length);
  const int n = segments >= 3.0 && segments < 1.0e8 ? static_cast<int>(segments) : 3;
  DomainLoop loop;
  loop.is_circle = true;
  loop.center = center;
  loop.radius = radius;
  for (int k = 0; k < n; ++k) {
    const double phi = 2.0 * M_PI * k / n;
    loop.polygon.push_back(center + radius * Eigen::Vector2d(std::cos(phi), std::sin(phi)));
  }
  return loop;
}

}  // namespace pqlayout
