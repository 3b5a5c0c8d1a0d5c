// MeasureExtractedMesh (quad_extraction.h): counts, face sides, valences, edge lengths, planarity,
// boundary deviation and corners of an extracted mesh.
#include "geometry/quad_extraction.h"

#include "geometry/quad_cleanup.h"

#include <algorithm>
#include <cmath>

#include "geometry/boundary_refinement.h"
#include "geometry/cap_fill.h"
#include "geometry/planarity.h"

namespace pqlayout {

ExtractedMeshMetrics MeasureExtractedMesh(const SurfaceModel& surface, const ExtractedMesh& extracted,
                                          double corner_angle_deg) {
  const PolyMesh& mesh = extracted.mesh;
  ExtractedMeshMetrics m;
  m.n_vertices = static_cast<int>(mesh.n_vertices());
  m.n_edges = static_cast<int>(mesh.n_edges());
  m.n_faces = static_cast<int>(mesh.n_faces());
  m.euler_characteristic = m.n_vertices - m.n_edges + m.n_faces;
  int quads = 0;
  double delta_sum = 0.0;
  for (const auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> polygon;
    bool touches_boundary = false;
    for (const auto v : mesh.fv_range(f)) {
      polygon.push_back(ToEigen(mesh.point(v)));
      touches_boundary |= mesh.is_boundary(v);
    }
    const int sides = static_cast<int>(polygon.size());
    ++m.face_sides[sides];
    quads += sides == 4;
    const double delta = PlanarityDelta(polygon);
    m.planarity_max = std::max(m.planarity_max, delta);
    delta_sum += delta;
    if (sides != 4 && !touches_boundary) {
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (const auto& p : polygon) centroid += p / sides;
      (IsCapFace(extracted, f) ? m.caps : m.interior_non_quads).push_back({sides, centroid});
    }
  }
  if (m.n_faces > 0) {
    m.quad_fraction = double(quads) / m.n_faces;
    m.planarity_mean = delta_sum / m.n_faces;
  }
  for (const auto v : mesh.vertices()) ++m.vertex_valence[static_cast<int>(mesh.valence(v))];
  m.edge_min = m.n_edges > 0 ? INFINITY : 0.0;
  for (const auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    m.edge_min = std::min(m.edge_min, length);
    m.edge_max = std::max(m.edge_max, length);
    m.edge_mean += length / m.n_edges;
  }
  // Boundary loops of the mesh and their distance to the reference boundary.
  const ReferenceBoundary reference(surface);
  const auto distance_to_reference = [&](const Eigen::Vector3d& p) { return reference.Distance(p); };
  std::set<int> seen;
  for (const auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen.count(h.idx())) continue;
    ++m.boundary_loops;
    auto walk = h;
    do {
      seen.insert(walk.idx());
      const Eigen::Vector3d a = ToEigen(mesh.point(mesh.from_vertex_handle(walk)));
      const Eigen::Vector3d b = ToEigen(mesh.point(mesh.to_vertex_handle(walk)));
      m.boundary_deviation_vertices = std::max(m.boundary_deviation_vertices, distance_to_reference(a));
      for (int s = 0; s <= 8; ++s)
        m.boundary_deviation_edges = std::max(m.boundary_deviation_edges, distance_to_reference(a + (b - a) * (s / 8.0)));
      walk = mesh.next_halfedge_handle(walk);
    } while (walk != h && seen.size() <= mesh.n_halfedges());
  }
  const std::vector<int> corners = surface.BoundaryCorners(corner_angle_deg * M_PI / 180.0);
  m.n_reference_corners = static_cast<int>(corners.size());
  for (const int c : corners) {
    const Eigen::Vector3d p = surface.position(c);
    for (const auto v : mesh.vertices())
      if ((ToEigen(mesh.point(v)) - p).norm() <= 1e-9 * (1.0 + p.norm())) {
        ++m.n_corner_vertices;
        break;
      }
  }
  return m;
}

const char* ShortEdgeBlocker(const ExtractedMesh& extracted, int u, int v) {
  extraction_internal::Polygons polygons;
  for (const auto vh : extracted.mesh.vertices()) polygons.position.push_back(ToEigen(extracted.mesh.point(vh)));
  polygons.origin = extracted.origin;
  for (const auto f : extracted.mesh.faces()) {
    std::vector<int> face;
    for (const auto vh : extracted.mesh.fv_range(f)) face.push_back(vh.idx());
    polygons.faces.push_back(std::move(face));
  }
  return extraction_internal::CollapseBlocker(polygons, u, v);
}

}  // namespace pqlayout
