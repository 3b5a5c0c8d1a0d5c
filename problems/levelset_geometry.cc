// Per-face geometry of the level-set problem (P1 gradients, shape operators, interior edges).
#include "problems/levelset_internal.h"

#include <algorithm>

#include "geometry/differential_operators.h"
#include "geometry/principal_directions.h"
#include "problems/residuals/conjugacy_residual.h"

namespace pqlayout {
namespace levelset_internal {


LevelSetGeometry Precompute(const SurfaceModel& surface) {
  LevelSetGeometry geo;
  geo.S = FaceShapeOperators(surface);
  geo.G.resize(surface.num_faces());
  geo.centroid.resize(surface.num_faces());
  double curvature_integral = 0.0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto g = FaceBasisGradients(surface, f);
    geo.G[f] << g[0], g[1], g[2];
    const auto ids = surface.face_vertices(f);
    geo.centroid[f] = (surface.position(ids[0]) + surface.position(ids[1]) + surface.position(ids[2])) / 3.0;
    curvature_integral += surface.face_area(f) * ConjugacyResidual::CurvatureSum(geo.S[f], surface.face_normal(f));
  }
  // μ = 10 % of the mean |κ1| + |κ2|: flat parts of a curved roof fall back to orthogonal
  // grid lines, the curved parts are conjugate.
  geo.flat_curvature = std::max(1e-12, 0.1 * curvature_integral / surface.total_area());
  return geo;
}

Eigen::Vector3d Gradient(const LevelSetGeometry& geo, const SurfaceModel& s, int f, const std::vector<double>& u) {
  const auto ids = s.face_vertices(f);
  return geo.G[f] * Eigen::Vector3d(u[ids[0]], u[ids[1]], u[ids[2]]);
}


Eigen::Matrix3d OrderedBasis(const LevelSetGeometry& geo, const SurfaceModel& s, int f, const std::array<int, 3>& order) {
  const auto ids = s.face_vertices(f);
  Eigen::Matrix3d ordered;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      if (ids[k] == order[c]) ordered.col(c) = geo.G[f].col(k);
  return ordered;
}

std::vector<InteriorEdge> InteriorEdges(const SurfaceModel& s, const LevelSetGeometry& geo) {
  const TriMesh& mesh = s.mesh();
  std::vector<InteriorEdge> edges;
  for (const auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    const auto h = mesh.halfedge_handle(e, 0), o = mesh.opposite_halfedge_handle(h);
    const int f = mesh.face_handle(h).idx(), g = mesh.face_handle(o).idx();
    InteriorEdge edge;
    edge.i = mesh.from_vertex_handle(h).idx();
    edge.j = mesh.to_vertex_handle(h).idx();
    edge.k = mesh.to_vertex_handle(mesh.next_halfedge_handle(h)).idx();
    edge.l = mesh.to_vertex_handle(mesh.next_halfedge_handle(o)).idx();
    edge.f = f;
    edge.g = g;
    edge.Gf = OrderedBasis(geo, s, f, {edge.i, edge.j, edge.k});
    edge.Gg = OrderedBasis(geo, s, g, {edge.i, edge.j, edge.l});
    edge.area = (s.face_area(f) + s.face_area(g)) / 3.0;
    edge.distance = (geo.centroid[f] - geo.centroid[g]).norm();
    edges.push_back(edge);
  }
  return edges;
}

std::vector<InteriorEdge> SmoothedEdges(const std::vector<InteriorEdge>& edges, const GuidanceField& g, double max_weight) {
  std::vector<InteriorEdge> smoothed;
  for (const InteriorEdge& e : edges)
    if (std::min(g.weight[e.f], g.weight[e.g]) <= max_weight) smoothed.push_back(e);
  return smoothed;
}

std::vector<SeamEdgeTerm> SeamEdgeTerms(const SurfaceModel& s, const LevelSetGeometry& geo, const SeamCut& cut) {
  std::vector<SeamEdgeTerm> terms;
  for (const auto& e : cut.seam_edges()) {
    const auto ids_f = s.face_vertices(e.minus_face), ids_g = s.face_vertices(e.plus_face);
    const TriMesh& m = s.mesh();
    const auto h = m.halfedge_handle(EdgeHandle(e.cut_edge_minus), 0);
    const int a = cut.original_vertex(m.from_vertex_handle(h).idx()), b = cut.original_vertex(m.to_vertex_handle(h).idx());
    SeamEdgeTerm t;
    t.path = e.path;
    t.i_minus = t.j_minus = t.k = t.i_plus = t.j_plus = t.l = -1;
    for (int c = 0; c < 3; ++c) {
      const int of = cut.original_vertex(ids_f[c]), og = cut.original_vertex(ids_g[c]);
      (of == a ? t.i_minus : of == b ? t.j_minus : t.k) = ids_f[c];
      (og == a ? t.i_plus : og == b ? t.j_plus : t.l) = ids_g[c];
    }
    t.Gf = OrderedBasis(geo, s, e.minus_face, {t.i_minus, t.j_minus, t.k});
    t.Gg = OrderedBasis(geo, s, e.plus_face, {t.i_plus, t.j_plus, t.l});
    t.area = (s.face_area(e.minus_face) + s.face_area(e.plus_face)) / 3.0;
    t.distance = (geo.centroid[e.minus_face] - geo.centroid[e.plus_face]).norm();
    terms.push_back(t);
  }
  return terms;
}

}  // namespace levelset_internal
}  // namespace pqlayout
