#include "geometry/remesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <glog/logging.h>

#include <cmath>
#include <vector>

namespace pqlayout {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

// CGAL 5.5's relaxation moves vertices of vertex_is_constrained_map as if they were interior
// (CGAL issue #8388, fixed in 6.1 by PR #8604): on a dome steep at its rim the four plan corners
// came out 0.35 m inside, where no boundary is, and the extraction then split boundary chords
// until its guard (268 vertices, a quad fraction of 0.15). Each corner goes back to where it
// was, unless that would turn one of its triangles over (none has in any case measured).
// Returns how many corners moved back.
int RestoreCorners(const std::vector<Kernel::Point_3>& original, CgalMesh::Property_map<CgalMesh::Vertex_index, bool> corner,
                   CgalMesh* mesh) {
  int restored = 0;
  for (const auto v : mesh->vertices()) {
    if (!corner[v] || original.empty()) continue;
    const Kernel::Point_3 moved = mesh->point(v);
    const Kernel::Point_3* nearest = &original.front();
    for (const auto& c : original)
      if (CGAL::squared_distance(c, moved) < CGAL::squared_distance(*nearest, moved)) nearest = &c;
    if (*nearest == moved) continue;
    std::vector<Kernel::Vector_3> before;
    for (const auto f : faces_around_target(mesh->halfedge(v), *mesh))
      if (f != CgalMesh::null_face()) before.push_back(PMP::compute_face_normal(f, *mesh));
    mesh->point(v) = *nearest;
    size_t k = 0;
    bool turned = false;
    for (const auto f : faces_around_target(mesh->halfedge(v), *mesh))
      if (f != CgalMesh::null_face()) turned |= !(PMP::compute_face_normal(f, *mesh) * before[k++] > 0.0);
    if (turned) mesh->point(v) = moved;
    else ++restored;
  }
  return restored;
}

}  // namespace

double MeanEdgeLength(const TriMesh& mesh) {
  double sum = 0.0;
  for (const auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return mesh.n_edges() > 0 ? sum / mesh.n_edges() : 0.0;
}

Status RemeshIsotropic(const SurfaceModel& surface, double edge_length, double corner_angle_deg, int iterations,
                       TriMesh* out) {
  if (!(edge_length > 0.0)) return Status::InvalidInput("remesh: edge length must be positive");
  CgalMesh mesh;
  std::vector<CgalMesh::Vertex_index> vertex(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Eigen::Vector3d p = surface.position(v);
    vertex[v] = mesh.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
  }
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    if (mesh.add_face(vertex[ids[0]], vertex[ids[1]], vertex[ids[2]]) == CgalMesh::null_face())
      return Status::Internal("remesh: CGAL refused reference triangle " + std::to_string(f));
  }
  auto corner = mesh.add_property_map<CgalMesh::Vertex_index, bool>("v:corner", false).first;
  std::vector<Kernel::Point_3> corners;
  for (const int v : surface.BoundaryCorners(corner_angle_deg * M_PI / 180.0)) {
    corner[vertex[v]] = true;
    corners.push_back(mesh.point(vertex[v]));
  }
  auto constrained = mesh.add_property_map<CgalMesh::Edge_index, bool>("e:constrained", false).first;
  for (const auto e : mesh.edges()) constrained[e] = mesh.is_border(e);
  PMP::isotropic_remeshing(faces(mesh), edge_length, mesh,
                           PMP::parameters::number_of_iterations(iterations)
                               .edge_is_constrained_map(constrained)
                               .vertex_is_constrained_map(corner)
                               .protect_constraints(false)
                               .collapse_constraints(true)
                               .relax_constraints(true));
  mesh.collect_garbage();
  if (const int restored = RestoreCorners(corners, corner, &mesh); restored > 0)
    VLOG(1) << "remesh: " << restored << " of " << corners.size() << " corners moved back where they were (CGAL #8388)";

  *out = TriMesh();
  std::vector<VertexHandle> handle(mesh.number_of_vertices());
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    handle[v.idx()] = out->add_vertex(TriMesh::Point(p.x(), p.y(), p.z()));
  }
  for (const auto f : mesh.faces()) {
    std::vector<VertexHandle> ids;
    for (const auto v : vertices_around_face(mesh.halfedge(f), mesh)) ids.push_back(handle[v.idx()]);
    if (!out->add_face(ids).is_valid())
      return Status::Internal("remesh: the remeshed surface is not manifold at face " + std::to_string(f.idx()));
  }
  return Status::Ok();
}

}  // namespace pqlayout
