#include "geometry/soup_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <tuple>

#include "geometry/mesh_validation.h"
#include "geometry/soup_edges.h"

namespace pqlayout {
namespace {

// The soup the repairs can work on (validation names what is wrong with any other) and the
// diagonal of its used vertices' bounding box; nullopt when it is not one.
std::optional<double> RepairableDiagonal(const PolygonSoup& soup) {
  double diagonal = 0.0;
  if (!CheckSoupFacesAndPoints(soup, &diagonal).ok()) return std::nullopt;
  return diagonal;
}

struct BoundaryEdge {
  int a, b, face;  // a → b as the face runs
};

std::vector<BoundaryEdge> BoundaryEdges(const std::vector<EdgeUse>& uses) {
  std::vector<BoundaryEdge> edges;
  ForEachEdge(uses, [&](size_t i, size_t count) {
    if (count != 1) return;
    const EdgeUse& u = uses[i];
    edges.push_back(u.forward ? BoundaryEdge{u.lo, u.hi, u.face} : BoundaryEdge{u.hi, u.lo, u.face});
  });
  return edges;
}

// Boundary vertices within tol of each other, not on a common triangle, become the first of
// them (vertex_of says which, for every vertex). Candidates are found by sorting along a direction no roof's boundary follows.
int WeldBoundary(PolygonSoup* soup, const std::vector<BoundaryEdge>& edges, double tol, std::vector<int>* vertex_of) {
  std::vector<int> vertices;
  for (const auto& e : edges) vertices.insert(vertices.end(), {e.a, e.b});
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  if (vertices.size() < 2) return 0;
  std::vector<int> slot(soup->points.size(), -1);
  for (size_t i = 0; i < vertices.size(); ++i) slot[vertices[i]] = static_cast<int>(i);
  std::vector<std::vector<int>> faces_of(vertices.size());  // the faces round each boundary vertex
  for (size_t f = 0; f < soup->faces.size(); ++f)
    for (const int v : soup->faces[f])
      if (slot[v] >= 0) faces_of[slot[v]].push_back(static_cast<int>(f));
  const Eigen::Vector3d d = Eigen::Vector3d(1.0, 0.7548776662, 0.5698402910).normalized();
  std::vector<std::pair<double, int>> order;
  for (const int v : vertices) order.emplace_back(d.dot(soup->points[v]), v);
  std::sort(order.begin(), order.end());
  DisjointSets sets(static_cast<int>(soup->points.size()));
  for (size_t i = 0; i < order.size(); ++i) {
    const int u = order[i].second;
    for (size_t j = i + 1; j < order.size() && order[j].first - order[i].first <= tol; ++j) {
      const int v = order[j].second;
      if ((soup->points[u] - soup->points[v]).norm() > tol) continue;
      const auto& fu = faces_of[slot[u]];
      const auto& fv = faces_of[slot[v]];
      const bool share = std::any_of(fu.begin(), fu.end(), [&](int f) { return std::count(fv.begin(), fv.end(), f); });
      if (!share) sets.Union(u, v);
    }
  }
  int welded = 0;
  for (const int v : vertices) welded += sets.Find(v) != v;
  if (welded == 0) return 0;
  for (auto& face : soup->faces)
    for (int& v : face) v = sets.Find(v);
  vertex_of->resize(soup->points.size());
  for (size_t v = 0; v < soup->points.size(); ++v) (*vertex_of)[v] = sets.Find(static_cast<int>(v));
  return welded;
}

// The boundary edges in a grid of cells as large as the longest of them, each edge in every
// cell its bounding box, widened by `reach`, touches: the edges near a point are those of the
// point's cell.
class BoundaryEdgeGrid {
 public:
  BoundaryEdgeGrid(const PolygonSoup& soup, const std::vector<BoundaryEdge>& edges, double reach_at_least)
      : soup_(soup), edges_(edges) {
    for (const auto& e : edges) cell_ = std::max(cell_, (soup.points[e.b] - soup.points[e.a]).norm());
    cell_ = std::max(cell_, reach_at_least) * 1.01;
    // Every edge shorter than 1e-4 m at 1e8 m: degenerate, left to validation.
    if (!(cell_ > kMaxSurfaceCoordinate * 1e-12)) return;
    const double reach = std::max(reach_at_least, 0.05 * cell_);
    for (size_t i = 0; i < edges.size(); ++i) {
      const Eigen::Vector3d& a = soup.points[edges[i].a];
      const Eigen::Vector3d& b = soup.points[edges[i].b];
      const Key lo = KeyOf(a.cwiseMin(b) - Eigen::Vector3d::Constant(reach));
      const Key hi = KeyOf(a.cwiseMax(b) + Eigen::Vector3d::Constant(reach));
      if (hi[0] - lo[0] > 3 || hi[1] - lo[1] > 3 || hi[2] - lo[2] > 3) continue;  // cannot be: cells ≥ every edge
      for (long long x = lo[0]; x <= hi[0]; ++x)
        for (long long y = lo[1]; y <= hi[1]; ++y)
          for (long long z = lo[2]; z <= hi[2]; ++z) grid_[{x, y, z}].push_back(static_cast<int>(i));
    }
  }

  struct Hit {
    int edge = -1;
    double t = 0.0, distance = INFINITY;
  };
  // The boundary edge whose interior lies nearest to vertex v, not more than
  // max(tol, relative × its length) off it, at least tol from its ends and not on one of v's
  // triangles (edge -1 if none). relative ≤ 0.05.
  Hit Nearest(int v, double tol, double relative) const {
    Hit best;
    const auto found = grid_.find(KeyOf(soup_.points[v]));
    if (found == grid_.end()) return best;
    const Eigen::Vector3d& p = soup_.points[v];
    for (const int i : found->second) {
      const auto& face = soup_.faces[edges_[i].face];
      if (std::count(face.begin(), face.end(), v)) continue;
      const Eigen::Vector3d& a = soup_.points[edges_[i].a];
      const Eigen::Vector3d ab = soup_.points[edges_[i].b] - a;
      const double t = (p - a).dot(ab) / ab.squaredNorm();
      if (!(t > 0.0 && t < 1.0)) continue;
      const double distance = (a + t * ab - p).norm(), length = ab.norm();
      if (distance > std::max(tol, relative * length) || t * length <= tol || (1.0 - t) * length <= tol) continue;
      if (distance < best.distance) best = {i, t, distance};
    }
    return best;
  }

 private:
  using Key = std::array<long long, 3>;
  Key KeyOf(const Eigen::Vector3d& p) const {
    return Key{std::llround(std::floor(p.x() / cell_)), std::llround(std::floor(p.y() / cell_)),
               std::llround(std::floor(p.z() / cell_))};
  }

  const PolygonSoup& soup_;
  const std::vector<BoundaryEdge>& edges_;
  double cell_ = 0.0;
  std::map<Key, std::vector<int>> grid_;
};

// Where a boundary vertex v lies on the interior of boundary edge e (within max(tol, 1e-3 ×
// its length), not one of v's triangles), e's triangle is split at v. At most one edge per
// triangle a pass: the caller repeats until nothing changes.
int ZipOnePass(PolygonSoup* soup, const std::vector<BoundaryEdge>& edges, double tol) {
  if (edges.empty()) return 0;
  const BoundaryEdgeGrid grid(*soup, edges, tol);
  // Per edge, the vertices to insert with their parameter along it.
  std::map<int, std::vector<std::pair<double, int>>> inserts;
  std::vector<char> done(soup->points.size(), 0);
  for (const auto& boundary : edges) {
    const int v = boundary.a;
    if (done[v]) continue;
    done[v] = 1;
    if (const auto hit = grid.Nearest(v, tol, 1e-3); hit.edge >= 0) inserts[hit.edge].emplace_back(hit.t, v);
  }
  std::vector<char> face_split(soup->faces.size(), 0);
  int zipped = 0;
  for (auto& [i, along] : inserts) {
    const BoundaryEdge& e = edges[i];
    if (face_split[e.face]) continue;
    face_split[e.face] = 1;
    std::sort(along.begin(), along.end());
    const auto face = soup->faces[e.face];
    const int k = static_cast<int>(std::find(face.begin(), face.end(), e.a) - face.begin());
    const int c = face[(k + 2) % 3];
    std::vector<int> chain{e.a};
    for (const auto& [t, v] : along) chain.push_back(v);
    chain.push_back(e.b);
    soup->faces[e.face] = {chain[0], chain[1], c};
    for (size_t s = 1; s + 1 < chain.size(); ++s) soup->faces.push_back({chain[s], chain[s + 1], c});
    zipped += static_cast<int>(along.size());
  }
  return zipped;
}

// Orients each connected part consistently and facing up (its vector area's z ≥ 0, so that a
// roof exported with its normals down lays out as the same roof: the principal curvatures
// change sign with the normal); a part standing on its side (|z| < 1e-3 of its vector area)
// keeps its majority's orientation. Counts the triangles that disagreed with their part and
// the parts turned up; false and no change if a part cannot be oriented.
bool OrientParts(PolygonSoup* soup, const std::vector<EdgeUse>& uses, SoupRepairs* repairs) {
  const int nf = static_cast<int>(soup->faces.size());
  // Across each of its (at most three) manifold edges: (face, 1 if they disagree), or -1.
  std::vector<std::array<std::pair<int, int>, 3>> neighbours(nf);
  std::vector<unsigned char> count_of(nf, 0);
  for (auto& n : neighbours) n.fill({-1, 0});
  ForEachEdge(uses, [&](size_t i, size_t count) {
    if (count != 2) return;
    const int f = uses[i].face, g = uses[i + 1].face, disagree = uses[i].forward == uses[i + 1].forward;
    neighbours[f][count_of[f]++] = {g, disagree};
    neighbours[g][count_of[g]++] = {f, disagree};
  });
  auto vector_area = [&](int f) {
    const auto& p = soup->points;
    const auto& v = soup->faces[f];
    return Eigen::Vector3d((p[v[1]] - p[v[0]]).cross(p[v[2]] - p[v[0]]));
  };
  std::vector<int> parity(nf, -1), flip;
  for (int seed = 0; seed < nf; ++seed) {
    if (parity[seed] >= 0) continue;
    std::vector<int> part{seed};
    parity[seed] = 0;
    for (size_t q = 0; q < part.size(); ++q) {
      for (const auto& [g, disagree] : neighbours[part[q]]) {
        if (g < 0) break;
        const int want = parity[part[q]] ^ disagree;
        if (parity[g] < 0) {
          parity[g] = want;
          part.push_back(g);
        } else if (parity[g] != want) {
          return false;
        }
      }
    }
    const long ones = std::count_if(part.begin(), part.end(), [&](int f) { return parity[f] == 1; });
    Eigen::Vector3d area = Eigen::Vector3d::Zero();  // as oriented like the parity-0 faces
    for (const int f : part) area += parity[f] == 0 ? vector_area(f) : Eigen::Vector3d(-vector_area(f));
    int turn = 2 * ones <= static_cast<long>(part.size()) ? 1 : 0;  // the minority
    if (std::abs(area.z()) >= 1e-3 * area.norm()) turn = area.z() > 0.0 ? 1 : 0;
    repairs->flipped += static_cast<int>(std::min<long>(ones, static_cast<long>(part.size()) - ones));
    const long turned = turn == 1 ? ones : static_cast<long>(part.size()) - ones;
    if (2 * turned > static_cast<long>(part.size())) ++repairs->turned_up;
    for (const int f : part)
      if (parity[f] == turn) flip.push_back(f);
  }
  for (const int f : flip) std::reverse(soup->faces[f].begin(), soup->faces[f].end());
  return true;
}

}  // namespace

double SuggestWeldTolerance(const PolygonSoup& soup) {
  if (!RepairableDiagonal(soup)) return 0.0;
  const auto edges = BoundaryEdges(SortedEdgeUses(soup));
  const BoundaryEdgeGrid grid(soup, edges, 0.0);
  double farthest = 0.0;
  std::vector<char> done(soup.points.size(), 0);
  for (const auto& boundary : edges) {
    if (done[boundary.a]) continue;
    done[boundary.a] = 1;
    if (const auto hit = grid.Nearest(boundary.a, 0.0, 0.05); hit.edge >= 0) farthest = std::max(farthest, hit.distance);
  }
  return farthest;
}

SoupRepairs RepairSurfaceSoup(PolygonSoup* soup, double weld_tolerance) {
  SoupRepairs repairs;
  const std::optional<double> diagonal = RepairableDiagonal(*soup);
  if (!diagonal) return repairs;
  repairs.tolerance = weld_tolerance > 0.0 ? weld_tolerance : 1e-6 * *diagonal;
  auto uses = SortedEdgeUses(*soup);
  repairs.welded = WeldBoundary(soup, BoundaryEdges(uses), repairs.tolerance, &repairs.vertex_of);
  if (repairs.welded > 0) uses = SortedEdgeUses(*soup);
  for (int pass = 0; pass < 8; ++pass) {
    const int zipped = ZipOnePass(soup, BoundaryEdges(uses), repairs.tolerance);
    if (zipped == 0) break;
    repairs.zipped += zipped;
    uses = SortedEdgeUses(*soup);
  }
  SoupRepairs oriented = repairs;
  if (OrientParts(soup, uses, &oriented)) repairs = oriented;
  return repairs;
}

}  // namespace pqlayout
