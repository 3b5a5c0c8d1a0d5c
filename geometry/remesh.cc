#include "geometry/remesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <vector>

namespace pqlayout {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

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
  for (const int v : surface.BoundaryCorners(corner_angle_deg * M_PI / 180.0)) corner[vertex[v]] = true;
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
