#include "geometry/quad_extraction.h"

#include "geometry/boundary_refinement.h"
#include "geometry/closest_point.h"
#include "geometry/quad_cleanup.h"
#include "geometry/quad_extraction_cells.h"
#include "geometry/planarity.h"
#include "geometry/polygon_shape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>

namespace pqlayout {
namespace {

using namespace extraction_internal;

// ---- Clean-up: geometry/quad_cleanup.h ------------------------------------------------------

std::vector<int> Padded(std::vector<int> kept, const std::vector<int>& points, const std::vector<Carrier>& carriers,
                        const std::vector<CutPoint>& cut) {
  const size_t n = points.size();
  while (kept.size() < 3 && kept.size() < n) {
    int best = -1;
    double best_score = -1.0;
    for (size_t k = 0; k < n; ++k) {
      if (std::find(kept.begin(), kept.end(), int(k)) != kept.end()) continue;
      double distance = kept.empty() ? 1.0 : INFINITY;
      for (const int q : kept) distance = std::min(distance, (cut[points[k]].position - cut[points[q]].position).norm());
      const bool boundary = carriers[k].kind == Carrier::kBoundary && carriers[(k + n - 1) % n].kind == Carrier::kBoundary;
      const double score = distance + (boundary ? 1e9 : 0.0);
      if (score > best_score) best_score = score, best = int(k);
    }
    kept.push_back(best);
    std::sort(kept.begin(), kept.end());
  }
  return kept;
}

// What the extraction needs to know about the surface it cuts besides its triangles: the
// reference boundary and corners (those of the original surface), and, for a surface cut
// open along seams, the seams and their transitions.
struct SurfaceInfo {
  std::vector<int> corners;  // vertices of the surface that is cut
  std::vector<char> vertex_on_boundary, edge_on_boundary;
  const SeamCut* seams = nullptr;
  const SeamTransitions* transitions = nullptr;
  std::vector<char> vertex_on_rim;  // on a cap's rim: a boundary here, not on the reference
  const SurfaceModel* reference = nullptr;  // the surface the output lies on, if not the one cut
};

// Per cut point, the point it stands for: the two sides of every seam identified (a vertex
// copy with its twin copy; the crossing of level L of a family with the minus edge with that
// of s·L + offset with the plus edge). The smallest id of each class stands for it.
std::vector<int> IdentifySeamPoints(const Cutter& cutter, const SeamCut& seams, const SeamTransitions& transitions) {
  const std::vector<CutPoint>& points = cutter.points();
  std::vector<int> parent(points.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  const auto unite = [&](int a, int b) {
    if (a < 0 || b < 0) return;
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  for (const SeamCopyPair& pair : seams.copy_pairs()) unite(cutter.VertexPointId(pair.minus), cutter.VertexPointId(pair.plus));
  std::unordered_map<int, const SeamEdge*> seam_of_minus_edge;
  for (const SeamEdge& e : seams.seam_edges()) seam_of_minus_edge[e.cut_edge_minus] = &e;
  for (size_t p = 0; p < points.size(); ++p) {
    if (points[p].edge < 0) continue;
    const auto seam = seam_of_minus_edge.find(points[p].edge);
    if (seam == seam_of_minus_edge.end()) continue;
    const int path = seam->second->path;
    const int offset[2] = {transitions.phi_offset[path], transitions.psi_offset[path]};
    // The point's key family has an integer value; the other may too (both lines cross the
    // edge there), and the other side may have keyed the point by either.
    for (const int family : {kPhi, kPsi}) {
      const double level = points[p].value[family];
      if (level != std::floor(level)) continue;
      const int q = cutter.EdgePointId(seam->second->cut_edge_plus, family,
                                       transitions.sign[path] * static_cast<int>(level) + offset[family]);
      if (q >= 0) {
        unite(int(p), q);
        break;
      }
    }
  }
  std::vector<int> canonical(points.size());
  for (size_t p = 0; p < points.size(); ++p) canonical[p] = find(int(p));
  return canonical;
}

// The label maps across every seam edge, both ways.
SeamLabelMaps LabelMapsAcross(const SeamCut& seams, const SeamTransitions& transitions) {
  SeamLabelMaps across;
  for (const SeamEdge& e : seams.seam_edges()) {
    LabelMap map;
    map.sign = transitions.sign[e.path];
    map.offset[kPhi] = transitions.phi_offset[e.path];
    map.offset[kPsi] = transitions.psi_offset[e.path];
    across[{e.minus_face, e.plus_face}] = map;
    map.forward = false;
    across[{e.plus_face, e.minus_face}] = map;
  }
  return across;
}

// Validated input: the extraction proper on `surface` (the original, or the cut surface).
// Output vertices are decided once for all loops, topologically: points where three or
// more cells meet (the outside of the surface counts as one), and boundary corners. Two
// regions along a shared chain thus keep the same points, even where ties make a chain lie
// on a φ line and a ψ line at once. Returns the polygons of the disc loops.
Polygons LoopPolygons(const std::vector<CutPoint>& cut, const std::vector<std::vector<int>>& loop_points,
                      const std::vector<std::vector<Carrier>>& loop_carriers, ExtractionStats* stats) {
  Polygons polygons;
  std::vector<int> vertex_of_point(cut.size(), -1);
  std::vector<std::vector<int>> cells_at(cut.size());
  const auto add_cell = [&](int point, int cell) {
    auto& cells = cells_at[point];
    if (std::find(cells.begin(), cells.end(), cell) == cells.end()) cells.push_back(cell);
  };
  for (size_t l = 0; l < loop_points.size(); ++l) {
    const size_t n = loop_points[l].size();
    for (size_t k = 0; k < n; ++k) {
      add_cell(loop_points[l][k], static_cast<int>(l));
      if (loop_carriers[l][k].kind == Carrier::kBoundary) {
        add_cell(loop_points[l][k], -1);
        add_cell(loop_points[l][(k + 1) % n], -1);
      }
    }
  }
  std::vector<char> is_output(cut.size(), 0);
  for (size_t p = 0; p < cut.size(); ++p) is_output[p] = cells_at[p].size() >= 3 || cut[p].corner;
  const auto kept_of = [&](size_t l) {
    std::vector<int> kept;
    for (size_t k = 0; k < loop_points[l].size(); ++k)
      if (is_output[loop_points[l][k]]) kept.push_back(int(k));
    return kept;
  };
  for (size_t l = 0; l < loop_points.size(); ++l) {
    const std::vector<int> kept = kept_of(l);
    if (kept.size() >= 3) continue;
    for (const int k : Padded(kept, loop_points[l], loop_carriers[l], cut)) is_output[loop_points[l][k]] = 1;
    ++stats->padded_faces;
  }
  for (size_t l = 0; l < loop_points.size(); ++l) {
    std::vector<int> face;
    for (const int k : kept_of(l)) {
      const int p = loop_points[l][k];
      if (vertex_of_point[p] < 0) {
        vertex_of_point[p] = static_cast<int>(polygons.position.size());
        polygons.position.push_back(cut[p].position);
        QuadMeshVertex origin;
        origin.face = cut[p].origin_face;
        origin.barycentric = cut[p].barycentric;
        origin.on_boundary = cut[p].on_boundary;
        origin.corner = cut[p].corner;
        polygons.origin.push_back(origin);
      }
      face.push_back(vertex_of_point[p]);
    }
    if (face.size() >= 3) polygons.faces.push_back(std::move(face));
  }

  return polygons;
}

// The clean-up (quad_cleanup.h) in its order, then the OpenMesh polygon mesh.
void CleanUpAndBuild(double min_edge_length, bool pair_boundary_triangles, Polygons* polygons_in, ExtractedMesh* out) {
  Polygons& polygons = *polygons_in;
  if (min_edge_length > 0.0) {
    while (const int collapsed = CollapseRound(min_edge_length, &polygons)) out->stats.collapsed_edges += collapsed;
  }
  out->stats.dropped_boundary_vertices = DropIdleBoundaryVertices(&polygons);
  out->stats.dropped_interior_vertices = DropInteriorValence2Vertices(&polygons);
  if (pair_boundary_triangles) {
    out->stats.resplit_boundary_pairs = ResplitBoundaryTrianglePentagonPairs(&polygons);
    out->stats.collapsed_boundary_triangles = CollapseBoundaryTriangles(kMinResplitAngle, &polygons);
    std::tie(out->stats.split_interior_polygons, out->stats.split_boundary_polygons) =
        SplitLargePolygons(kMinResplitAngle, &polygons, min_edge_length);
  }
  out->stats.floating_faces = DropFloatingParts(&polygons);
  Compact(&polygons);

  out->mesh = BuildPolyMesh(polygons.position, polygons.faces, &out->stats.rejected_faces);
  out->origin = polygons.origin;
}

// The centre vertices SplitLargePolygons added moved from their polygon's centroid onto the
// surface.
void PlaceCentreVertices(const SurfaceModel& surface, ExtractedMesh* out) {
  for (size_t v = 0; v < out->origin.size(); ++v) {
    QuadMeshVertex& origin = out->origin[v];
    if (!origin.centre) continue;
    const SurfacePoint p = surface.closest_points().OnSurface(ToEigen(out->mesh.point(VertexHandle(v))));
    out->mesh.set_point(VertexHandle(v), ToOpenMesh(p.point));
    origin.face = p.element;
    origin.barycentric = TriangleBarycentric(surface, p.element, p.point);
    ++out->stats.centre_vertices;
  }
}

Status Extract(const SurfaceModel& surface, const SurfaceInfo& info, const std::vector<double>& phi,
               const std::vector<double>& psi, double min_edge_length, ExtractedMesh* out,
               bool pair_boundary_triangles) {
  Cutter cutter(surface, phi, psi, info.corners, info.vertex_on_boundary, info.edge_on_boundary);
  std::vector<Piece> pieces;
  for (int f = 0; f < surface.num_faces(); ++f) cutter.CutFace(f, &pieces);
  const std::vector<CutPoint>& cut = cutter.points();

  std::vector<int> canonical(cut.size());
  std::iota(canonical.begin(), canonical.end(), 0);
  SeamLabelMaps across;
  if (info.seams != nullptr) {
    canonical = IdentifySeamPoints(cutter, *info.seams, *info.transitions);
    across = LabelMapsAcross(*info.seams, *info.transitions);
  }
  Regions regions(pieces, canonical, across);
  const auto loops = regions.Loops();
  *out = ExtractedMesh();
  if (info.seams != nullptr) {
    for (size_t p = 0; p < pieces.size(); ++p) {
      const Polygon& c = pieces[p].corners;
      for (size_t k = 0; k < c.size(); ++k) {
        const int edge = cutter.CommonEdge(c[k].point, c[(k + 1) % c.size()].point);
        if (edge >= 0 && info.seams->is_seam_edge(edge) && !regions.Twin({int(p), int(k)}))
          ++out->stats.unmatched_seam_edges;
      }
    }
  }
  // The loop of every disc region: its points and the curve each loop edge lies on
  // (reference boundary edges as one curve; interior reference edges along a level line as
  // that line).
  std::vector<std::vector<int>> loop_points;
  std::vector<std::vector<Carrier>> loop_carriers;
  for (const auto& [region, region_loops] : loops) {
    if (region_loops.size() != 1) {
      ++out->stats.regions_with_holes;
      continue;
    }
    std::vector<int> points;
    std::vector<Carrier> carriers;
    for (const PieceEdge& e : region_loops[0]) {
      const int a = regions.From(e), b = regions.To(e);
      Carrier c = regions.PieceCarrier(e);
      const int edge = cutter.CommonEdge(a, b);
      if (edge >= 0 && info.edge_on_boundary[edge]) {
        c = {Carrier::kBoundary, 0};
      } else if (c.kind == Carrier::kReferenceEdge) {
        for (const int family : {kPhi, kPsi})
          if (c.kind == Carrier::kReferenceEdge && cut[a].value[family] == cut[b].value[family] &&
              cut[a].value[family] == std::floor(cut[a].value[family]))
            c = {family, static_cast<int>(cut[a].value[family])};
      }
      points.push_back(canonical[a]);
      carriers.push_back(c);
    }
    if (points.size() < 3) continue;
    loop_points.push_back(std::move(points));
    loop_carriers.push_back(std::move(carriers));
  }
  Polygons polygons = LoopPolygons(cut, loop_points, loop_carriers, &out->stats);
  if (info.reference != nullptr) {  // the clean-up measures edges and angles where they will lie
    const ClosestPointQuery& query = info.reference->closest_points();
    for (size_t v = 0; v < polygons.position.size(); ++v) {
      QuadMeshVertex origin = polygons.origin[v];
      int nearest;  // a point on a boundary edge weighs only its two ends, of one loop
      origin.barycentric.maxCoeff(&nearest);
      if (info.vertex_on_rim[surface.face_vertices(origin.face)[nearest]]) origin.on_boundary = origin.corner = false;
      polygons.position[v] = PlacedOnReference(query, origin, polygons.position[v]).point;
    }
  }
  CleanUpAndBuild(min_edge_length, pair_boundary_triangles, &polygons, out);
  PlaceCentreVertices(surface, out);
  return Status::Ok();
}

// The vertices of `surface` on a cap's rim: every vertex of a boundary loop that lies within
// radius + cap_reach of a cap's centre (ExtractQuadMesh).
std::vector<char> CapRimVertices(const SurfaceModel& surface, const std::vector<CapHole>& caps, double cap_reach) {
  std::vector<char> on_rim(surface.num_vertices(), 0);
  for (const BoundaryLoop& loop : surface.boundary_loops())
    for (const CapHole& cap : caps)
      if (std::all_of(loop.vertices.begin(), loop.vertices.end(), [&](VertexHandle v) {
            return (surface.position(v.idx()) - cap.centre).norm() < cap.radius + cap_reach;
          }))
        for (const VertexHandle v : loop.vertices) on_rim[v.idx()] = 1;
  return on_rim;
}

// The boundary corners of `surface` (turning by more than corner_angle_deg) off the rims.
std::vector<int> CornersOffCapRims(const SurfaceModel& surface, double corner_angle_deg,
                                   const std::vector<char>& on_rim) {
  std::vector<int> corners;
  for (const int v : surface.BoundaryCorners(corner_angle_deg * M_PI / 180.0))
    if (!on_rim[v]) corners.push_back(v);
  return corners;
}

Status CheckFinite(const std::vector<double>& phi, const std::vector<double>& psi) {
  for (size_t v = 0; v < phi.size(); ++v)
    if (!std::isfinite(phi[v]) || !std::isfinite(psi[v]) || std::abs(phi[v]) > 1e6 || std::abs(psi[v]) > 1e6)
      return Status::InvalidInput("extract: φ or ψ is not finite (or absurdly large) at vertex " + std::to_string(v));
  return Status::Ok();
}

}  // namespace

SurfacePoint PlacedOnReference(const ClosestPointQuery& reference, const QuadMeshVertex& origin,
                               const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = origin.on_boundary && !origin.corner ? reference.OnBoundary(p).point : p;
  SurfacePoint on = reference.OnSurface(q);
  if (origin.on_boundary) on.point = q;
  return on;
}

Status ExtractQuadMesh(const SurfaceModel& surface, const std::vector<double>& phi, const std::vector<double>& psi,
                       double corner_angle_deg, double min_edge_length, ExtractedMesh* out,
                       bool pair_boundary_triangles, const std::vector<CapHole>& caps, double cap_reach,
                       const SurfaceModel* reference) {
  const int nv = surface.num_vertices();
  if (static_cast<int>(phi.size()) != nv || static_cast<int>(psi.size()) != nv)
    return Status::InvalidInput("extract: φ and ψ need one value per reference vertex (" + std::to_string(nv) + ")");
  PQ_RETURN_IF_ERROR(CheckFinite(phi, psi));
  SurfaceInfo info;
  info.vertex_on_rim = CapRimVertices(surface, caps, cap_reach);
  info.corners = CornersOffCapRims(surface, corner_angle_deg, info.vertex_on_rim);
  info.vertex_on_boundary.resize(nv);
  for (int v = 0; v < nv; ++v) info.vertex_on_boundary[v] = surface.is_boundary(v);
  info.edge_on_boundary.resize(surface.mesh().n_edges());
  for (const auto e : surface.mesh().edges()) info.edge_on_boundary[e.idx()] = surface.mesh().is_boundary(e);
  info.reference = reference;
  return Extract(surface, info, phi, psi, min_edge_length, out, pair_boundary_triangles);
}

Status ExtractQuadMesh(const SurfaceModel& surface, const SeamTransitions& seams, const std::vector<double>& phi_cut,
                       const std::vector<double>& psi_cut, double corner_angle_deg, double min_edge_length,
                       ExtractedMesh* out, bool pair_boundary_triangles, const std::vector<CapHole>& caps,
                       double cap_reach, const SurfaceModel* reference) {
  if (seams.cut == nullptr) return Status::InvalidInput("extract: seam transitions without a seam cut");
  const SeamCut& seam_cut = *seams.cut;
  const SurfaceModel& cut = seam_cut.cut();
  const int paths = seam_cut.num_paths();
  if (static_cast<int>(seams.sign.size()) != paths || static_cast<int>(seams.phi_offset.size()) != paths ||
      static_cast<int>(seams.psi_offset.size()) != paths)
    return Status::InvalidInput("extract: seam transitions need one sign and offset per seam path (" +
                                std::to_string(paths) + ")");
  for (int p = 0; p < paths; ++p)
    if ((seams.sign[p] != 1 && seams.sign[p] != -1) || std::abs(seams.phi_offset[p]) > 1000000 ||
        std::abs(seams.psi_offset[p]) > 1000000)
      return Status::InvalidInput("extract: seam path " + std::to_string(p) + ": sign must be ±1 (offsets bounded)");
  if (cut.num_faces() != surface.num_faces())
    return Status::InvalidInput("extract: the seam cut has " + std::to_string(cut.num_faces()) +
                                " faces, the surface " + std::to_string(surface.num_faces()));
  for (int f = 0; f < cut.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (seam_cut.original_vertex(cut.face_vertices(f)[k]) != surface.face_vertices(f)[k])
        return Status::InvalidInput("extract: the seam cut is not a cut of this surface (face " + std::to_string(f) + ")");
  const int nv = cut.num_vertices();
  if (static_cast<int>(phi_cut.size()) != nv || static_cast<int>(psi_cut.size()) != nv)
    return Status::InvalidInput("extract: φ and ψ need one value per vertex of the cut surface (" +
                                std::to_string(nv) + ")");
  PQ_RETURN_IF_ERROR(CheckFinite(phi_cut, psi_cut));

  // The transitions made exact: values within kSnap of a level snap to it on both sides (so
  // both sides take the same tie decisions), then the plus copy takes s·u₋ + offset and a
  // single-copy tip the fixed point offset / 2 of u ↦ −u + offset.
  std::vector<double> values[2] = {phi_cut, psi_cut};
  double mismatch = 0.0;
  for (const SeamCopyPair& pair : seam_cut.copy_pairs()) {
    const int sign = seams.sign[pair.path];
    const int offset[2] = {seams.phi_offset[pair.path], seams.psi_offset[pair.path]};
    for (const int family : {kPhi, kPsi}) {
      std::vector<double>& u = values[family];
      u[pair.minus] = Snap(u[pair.minus]);
      double exact;
      if (pair.minus != pair.plus) {
        exact = sign * u[pair.minus] + offset[family];
      } else if (sign < 0) {
        exact = 0.5 * offset[family];
      } else {
        exact = offset[family] == 0 ? u[pair.minus] : INFINITY;  // no fixed point
      }
      const double error = std::abs(u[pair.plus] - exact);
      if (!(error <= kSeamTransitionTolerance * std::max(1.0, std::abs(exact))))
        return Status::InvalidInput("extract: seam path " + std::to_string(pair.path) + ": " +
                                    (family == kPhi ? "φ" : "ψ") + " at vertex " +
                                    std::to_string(pair.original_vertex) + " violates the transition u+ = " +
                                    std::to_string(sign) + "·u- + " + std::to_string(offset[family]) + " by " +
                                    std::to_string(error) + " levels");
      mismatch = std::max(mismatch, error);
      u[pair.plus] = Snap(exact);
    }
  }
  SurfaceInfo info;
  info.seams = &seam_cut;
  info.transitions = &seams;
  info.reference = reference;
  std::vector<char> is_corner(surface.num_vertices(), 0);
  const std::vector<char> on_rim = CapRimVertices(surface, caps, cap_reach);
  for (const int v : CornersOffCapRims(surface, corner_angle_deg, on_rim)) is_corner[v] = 1;
  info.vertex_on_boundary.resize(nv);
  for (int v = 0; v < nv; ++v) {
    const int original = seam_cut.original_vertex(v);
    info.vertex_on_boundary[v] = surface.is_boundary(original);
    info.vertex_on_rim.push_back(on_rim[original]);
    if (is_corner[original]) info.corners.push_back(v);
  }
  info.edge_on_boundary.resize(cut.mesh().n_edges());
  for (const auto e : cut.mesh().edges())
    info.edge_on_boundary[e.idx()] = cut.mesh().is_boundary(e) && !seam_cut.is_seam_edge(e.idx());
  PQ_RETURN_IF_ERROR(Extract(cut, info, values[kPhi], values[kPsi], min_edge_length, out, pair_boundary_triangles));
  out->stats.seam_transition_mismatch = mismatch;
  return Status::Ok();
}

}  // namespace pqlayout
