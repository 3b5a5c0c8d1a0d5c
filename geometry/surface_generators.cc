// Built-in surfaces: each generator is a height field (planar domain + z = f(x, y)). The
// domain is triangulated by MeshPlanarDomain, every vertex is lifted to the surface, and the
// lifted mesh is remeshed on the surface (edge splits, Delaunay flips, tangential smoothing)
// so that edge length and angles hold in space and not only in the plan.
#include "geometry/surface_generators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/height_field.h"
#include "geometry/planar_domain_mesher.h"
#include "geometry/roof_generators.h"

namespace pqlayout {
namespace {

using GC = GreatCourtDimensions;
constexpr double kGreatCourtLambda = 0.5;  // λ of the SPEC formula
constexpr double kGreatCourtMu = 14.0;     // μ of the SPEC formula

// β of the SPEC formula: blends the corner correction in from the ring (β = 0 at r = a) and
// out towards the rectangle (β = 0 there). Each corner term √(p²+q²)/(pq) is written as
// √(1/p² + 1/q²), which has no 0/0 near the rectangle.
double GreatCourtBeta(double x, double y, double r) {
  if (x <= -GC::b || x >= GC::b || y <= -GC::d || y >= GC::c) return 0.0;
  const double east = 1.0 / (GC::b - x), west = 1.0 / (GC::b + x);
  const double north = 1.0 / (GC::c - y), south = 1.0 / (GC::d + y);
  const double corners = std::hypot(east, north) + std::hypot(east, south) +
                         std::hypot(west, north) + std::hypot(west, south);
  return (1.0 - GC::a / r) / corners;
}

Status RequireRectangle(const GeneratorParams& params) {
  PQ_RETURN_IF_ERROR(RequirePositive(params.width, "surface.width"));
  return RequirePositive(params.depth, "surface.depth");
}

Status GreatCourt(const GeneratorParams& params, HeightField* field) {
  field->domain = {Rectangle(-GC::b, GC::b, -GC::d, GC::c),
                   CircleLoop(Eigen::Vector2d::Zero(), GC::a, params.edge_length)};
  field->height = GreatCourtHeight;
  return Status::Ok();
}

Status Dome(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireRectangle(params));
  PQ_RETURN_IF_ERROR(RequirePositive(params.rise, "surface.rise"));
  field->domain = {CenteredRectangle(params)};
  const double half_width = 0.5 * params.width, half_depth = 0.5 * params.depth;
  const double rise = params.rise;
  field->height = [=](double x, double y) {
    const double u = x / half_width, v = y / half_depth;
    return rise * (1.0 - 0.5 * (u * u + v * v));
  };
  return Status::Ok();
}

Status Hypar(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireRectangle(params));
  PQ_RETURN_IF_ERROR(RequirePositive(params.rise, "surface.rise"));
  field->domain = {CenteredRectangle(params)};
  const double scale = params.rise / (0.25 * params.width * params.depth);
  field->height = [=](double x, double y) { return scale * x * y; };
  return Status::Ok();
}

// Circular-arc vault over the x span: radius R = (w²/4 + rise²) / (2 rise), supports at z = 0.
Status Barrel(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireRectangle(params));
  PQ_RETURN_IF_ERROR(RequirePositive(params.rise, "surface.rise"));
  if (params.rise >= 0.5 * params.width) {
    return Status::InvalidInput(
        "surface.rise of a barrel must be less than half of surface.width (a higher arc is "
        "not a height field)");
  }
  field->domain = {CenteredRectangle(params)};
  const double rise = params.rise;
  const double radius = (0.25 * params.width * params.width + rise * rise) / (2.0 * rise);
  field->height = [=](double x, double) {
    return std::sqrt(radius * radius - x * x) - (radius - rise);
  };
  return Status::Ok();
}

Status Plane(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireRectangle(params));
  field->domain = {CenteredRectangle(params)};
  field->height = [](double, double) { return 0.0; };
  return Status::Ok();
}

Status Disk(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequirePositive(params.width, "surface.width"));
  field->domain = {CircleLoop(Eigen::Vector2d::Zero(), 0.5 * params.width, params.edge_length)};
  field->height = [](double, double) { return 0.0; };
  return Status::Ok();
}

Status Annulus(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequirePositive(params.width, "surface.width"));
  PQ_RETURN_IF_ERROR(RequirePositive(params.depth, "surface.depth"));
  if (params.depth >= params.width) {
    return Status::InvalidInput(
        "surface.depth (inner diameter of the annulus) must be less than surface.width (outer "
        "diameter)");
  }
  const Eigen::Vector2d center = Eigen::Vector2d::Zero();
  field->domain = {CircleLoop(center, 0.5 * params.width, params.edge_length),
                   CircleLoop(center, 0.5 * params.depth, params.edge_length)};
  field->height = [](double, double) { return 0.0; };
  return Status::Ok();
}

struct Generator {
  std::string name;
  Status (*build)(const GeneratorParams&, HeightField*);
};

const std::vector<Generator>& Generators() {
  static const std::vector<Generator> generators = {{"great_court", GreatCourt},
                                                    {"dome", Dome},
                                                    {"hypar", Hypar},
                                                    {"barrel", Barrel},
                                                    {"disk", Disk},
                                                    {"annulus", Annulus},
                                                    {"plane", Plane},
                                                    {"dome_circular", DomeCircular},
                                                    {"saddle_elliptic", SaddleElliptic},
                                                    {"canopy", Canopy},
                                                    {"l_shape", LShape},
                                                    {"hole_offcentre", HoleOffCentre},
                                                    {"two_holes", TwoHoles},
                                                    {"wavy", Wavy}};
  return generators;
}

std::string JoinedNames() {
  std::string joined;
  for (const std::string& name : GeneratorNames()) {
    joined += (joined.empty() ? "" : ", ") + name;
  }
  return joined;
}

const Generator* FindGenerator(const std::string& name) {
  for (const Generator& generator : Generators()) {
    if (generator.name == name) return &generator;
  }
  return nullptr;
}

OpenMesh::Vec3d Lift(const HeightField& field, const Eigen::Vector2d& q) {
  return {q.x(), q.y(), field.height(q.x(), q.y())};
}

Eigen::Vector2d PlanPosition(const TriMesh& mesh, VertexHandle v) {
  const OpenMesh::Vec3d& p = mesh.point(v);
  return {p[0], p[1]};
}

// Twice the signed plan area of the triangle (a, b, c): positive if counter-clockwise.
double PlanOrientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - a, v = c - a;
  return u.x() * v.y() - u.y() * v.x();
}

// Cotangent of the angle at `apex` of the triangle (apex, a, b) in space.
double SpaceCotangent(const TriMesh& mesh, VertexHandle apex, VertexHandle a, VertexHandle b) {
  const Eigen::Vector3d u = ToEigen(mesh.point(a) - mesh.point(apex));
  const Eigen::Vector3d v = ToEigen(mesh.point(b) - mesh.point(apex));
  return u.dot(v) / u.cross(v).norm();
}

// Lifts each planar point to (x, y, height(x, y)); counter-clockwise triangles in the plane
// give faces whose normals point up.
void LiftToMesh(const PlanarTriangulation& plan, const HeightField& field, TriMesh* mesh) {
  mesh->clear();
  std::vector<VertexHandle> vertices;
  vertices.reserve(plan.points.size());
  for (const Eigen::Vector2d& p : plan.points) vertices.push_back(mesh->add_vertex(Lift(field, p)));
  for (const std::array<int, 3>& t : plan.triangles) {
    mesh->add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  }
}

// The plan position halfway along the edge p-q. On a boundary edge of a circular loop it is
// projected onto the circle; on a straight loop segment the midpoint is already on it (and
// exactly so on an axis-parallel one).
Eigen::Vector2d BoundaryAwareMidpoint(const HeightField& field, const Eigen::Vector2d& p,
                                      const Eigen::Vector2d& q, bool on_boundary) {
  const Eigen::Vector2d midpoint = 0.5 * (p + q);
  if (!on_boundary) return midpoint;
  for (const DomainLoop& loop : field.domain) {
    if (!loop.is_circle) continue;
    const double tolerance = 1e-9 * loop.radius;
    if (std::abs((p - loop.center).norm() - loop.radius) <= tolerance &&
        std::abs((q - loop.center).norm() - loop.radius) <= tolerance) {
      return loop.center + loop.radius * (midpoint - loop.center).normalized();
    }
  }
  return midpoint;
}

// Splits every edge longer than max_length (in space) at its plan midpoint; new boundary
// vertices lie on the domain loops.
void SplitLongEdges(const HeightField& field, double max_length, TriMesh* mesh) {
  std::vector<EdgeHandle> long_edges;
  for (EdgeHandle e : mesh->edges()) {
    if (mesh->calc_edge_length(e) > max_length) long_edges.push_back(e);
  }
  for (EdgeHandle e : long_edges) {
    const HalfedgeHandle h = mesh->halfedge_handle(e, 0);
    const Eigen::Vector2d midpoint =
        BoundaryAwareMidpoint(field, PlanPosition(*mesh, mesh->from_vertex_handle(h)),
                              PlanPosition(*mesh, mesh->to_vertex_handle(h)), mesh->is_boundary(e));
    mesh->split(e, Lift(field, midpoint));
  }
}

// Flips interior edge e if its two opposite angles in space sum to more than π (it is not
// locally Delaunay on the surface: cot α + cot β < 0) and both new triangles are
// counter-clockwise in the plan. *blocked: it would have been flipped but OpenMesh refused (the
// new diagonal's ends are already joined), an answer that depends on edges outside its quad.
bool FlipIfNotDelaunay(EdgeHandle e, TriMesh* mesh, bool* blocked) {
  *blocked = false;
  if (mesh->is_boundary(e)) return false;
  const HalfedgeHandle h = mesh->halfedge_handle(e, 0);
  const HalfedgeHandle twin = mesh->halfedge_handle(e, 1);
  const VertexHandle p = mesh->from_vertex_handle(h), q = mesh->to_vertex_handle(h);
  const VertexHandle a = mesh->to_vertex_handle(mesh->next_halfedge_handle(h));
  const VertexHandle b = mesh->to_vertex_handle(mesh->next_halfedge_handle(twin));
  constexpr double kTolerance = 1e-9;
  if (SpaceCotangent(*mesh, a, p, q) + SpaceCotangent(*mesh, b, q, p) >= -kTolerance) {
    return false;
  }
  // The quad p, b, q, a is counter-clockwise; the diagonal a-b must stay inside it.
  const Eigen::Vector2d pp = PlanPosition(*mesh, p), pq = PlanPosition(*mesh, q);
  const Eigen::Vector2d pa = PlanPosition(*mesh, a), pb = PlanPosition(*mesh, b);
  if (PlanOrientation(pp, pb, pa) <= 0.0 || PlanOrientation(pb, pq, pa) <= 0.0) return false;
  if (!mesh->is_flip_ok(e)) {
    *blocked = true;
    return false;
  }
  mesh->flip(e);
  return true;
}

// Sweeps over every edge in index order until a sweep flips none. An edge is tested again
// only if a flip since its last test changed its quad (the flipped edge and the four around
// it) or OpenMesh refused its flip: vertices do not move here, so an unchanged quad gives the
// same answer, and the flips are exactly those of testing every edge in every sweep, in the
// same order, for a fraction of the cotangents (968k-triangle Great Court: 12.5 → 9.4 s).
void FlipToSurfaceDelaunay(TriMesh* mesh) {
  constexpr int kMaxSweeps = 20;  // flips on a curved surface need not settle; bound them
  std::vector<char> dirty(mesh->n_edges(), 1);
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    int flips = 0;
    for (EdgeHandle e : mesh->edges()) {
      if (!dirty[e.idx()]) continue;
      bool blocked = false;
      const bool flipped = FlipIfNotDelaunay(e, mesh, &blocked);
      dirty[e.idx()] = blocked;
      if (!flipped) continue;
      ++flips;
      dirty[e.idx()] = 1;
      for (const HalfedgeHandle h : {mesh->halfedge_handle(e, 0), mesh->halfedge_handle(e, 1)})
        for (HalfedgeHandle g = mesh->next_halfedge_handle(h); g != h; g = mesh->next_halfedge_handle(g))
          dirty[mesh->edge_handle(g).idx()] = 1;
    }
    if (flips == 0) return;
  }
}

// Whether moving v to plan position q would fold one of its triangles in the plan.
bool FoldsInPlan(const TriMesh& mesh, VertexHandle v, const Eigen::Vector2d& q) {
  for (HalfedgeHandle h : mesh.voh_range(v)) {
    const HalfedgeHandle opposite = mesh.next_halfedge_handle(h);
    if (PlanOrientation(q, PlanPosition(mesh, mesh.from_vertex_handle(opposite)),
                        PlanPosition(mesh, mesh.to_vertex_handle(opposite))) <= 0.0)
      return true;
  }
  return false;
}

// The smallest angle in space of the triangles round v.
double SmallestAngleAround(const TriMesh& mesh, VertexHandle v) {
  double smallest = M_PI;
  for (FaceHandle f : mesh.vf_range(v)) {
    std::array<Eigen::Vector3d, 3> p;
    int k = 0;
    for (VertexHandle u : mesh.fv_range(f)) p[k++] = ToEigen(mesh.point(u));
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
      smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)));
    }
  }
  return smallest;
}

// A vertex whose triangles have an angle below 20° in space (next to a graded boundary on a
// steep slope, where the boundary vertices cannot move) goes to the place of a 9 × 9 plan grid
// round it, ±0.5 of its shortest edge, where the smallest angle round it is largest without
// folding a triangle in the plan.
void PlaceForAngles(const HeightField& field, VertexHandle v, TriMesh* mesh) {
  constexpr int kGrid = 4;
  const Eigen::Vector2d centre = PlanPosition(*mesh, v);
  double reach = INFINITY;
  for (VertexHandle u : mesh->vv_range(v)) reach = std::min(reach, 0.5 * (PlanPosition(*mesh, u) - centre).norm());
  OpenMesh::Vec3d best = mesh->point(v);
  double best_angle = SmallestAngleAround(*mesh, v);
  for (int i = -kGrid; i <= kGrid; ++i)
    for (int j = -kGrid; j <= kGrid; ++j) {
      const Eigen::Vector2d q = centre + reach / kGrid * Eigen::Vector2d(i, j);
      if (FoldsInPlan(*mesh, v, q)) continue;
      mesh->set_point(v, Lift(field, q));
      const double angle = SmallestAngleAround(*mesh, v);
      if (angle > best_angle) best_angle = angle, best = mesh->point(v);
    }
  mesh->set_point(v, best);
}

// Moves each interior vertex to the plan position under the area-weighted centroid of its
// incident triangles (a tangential Lloyd step), unless that would fold a triangle in the plan
// or, with `guard`, take the smallest angle round it below kSmoothMinAngle (and below what it
// was): where the plan mesh grades from short boundary segments (an opening drawn as a
// circle), the step towards the larger triangles flattened the small ones to 15–18° in space.
void SmoothInteriorVertices(const HeightField& field, bool guard, TriMesh* mesh) {
  constexpr double kSmoothMinAngle = 20.0 * M_PI / 180.0;
  for (VertexHandle v : mesh->vertices()) {
    if (mesh->is_boundary(v)) continue;
    Eigen::Vector3d weighted_centroid = Eigen::Vector3d::Zero();
    double area = 0.0;
    for (FaceHandle f : mesh->vf_range(v)) {
      const double face_area = mesh->calc_face_area(f);
      weighted_centroid += face_area * ToEigen(mesh->calc_face_centroid(f));
      area += face_area;
    }
    const Eigen::Vector2d target = (weighted_centroid / area).head<2>();
    const bool folds = FoldsInPlan(*mesh, v, target);
    if (!guard) {
      if (!folds) mesh->set_point(v, Lift(field, target));
      continue;
    }
    const OpenMesh::Vec3d before = mesh->point(v);
    const double angle_before = SmallestAngleAround(*mesh, v);
    if (!folds) {
      mesh->set_point(v, Lift(field, target));
      const double angle_after = SmallestAngleAround(*mesh, v);
      if (angle_after < kSmoothMinAngle && angle_after < angle_before) mesh->set_point(v, before);
    }
    if (SmallestAngleAround(*mesh, v) < kSmoothMinAngle) PlaceForAngles(field, v, mesh);
  }
}

// The planar mesh is isotropic in the plan, but a steep height field stretches it (the Great
// Court rises with slope up to 1.4 from its north edge, which lengthens edges by up to 1.7
// and flattens triangles). A few rounds of isotropic remeshing on the surface restore edge
// length and shape in space. Every vertex stays on z = f(x, y); boundary vertices never move.
// guard: SmoothInteriorVertices' angle guard (GenerateSurface: where the plan mesh grades).
// rounds: 5, or 2 for a plan seeded with a lattice (planar_domain_mesher.cc, from 200k
// triangles), which is isotropic before lifting: on the 962k-triangle Great Court rounds 3–5
// took 1.2 s and changed the mean smallest angle by 0.005° (56.003° against 55.998°), the
// smallest by 0.6° (23.6° against 23.0°).
void RemeshOnSurface(const HeightField& field, double edge_length, bool guard, int rounds, TriMesh* mesh) {
  constexpr double kMaxLengthRatio = 4.0 / 3.0;  // as in Botsch & Kobbelt 2004
  for (int round = 0; round < rounds; ++round) {
    SplitLongEdges(field, kMaxLengthRatio * edge_length, mesh);
    FlipToSurfaceDelaunay(mesh);
    SmoothInteriorVertices(field, guard, mesh);
  }
  FlipToSurfaceDelaunay(mesh);
}

}  // namespace

double GreatCourtHeight(double x, double y) {
  const double r = std::hypot(x, y);
  const double theta = std::atan2(y, x);
  const double psi = (1.0 - x / GC::b) * (1.0 + x / GC::b) * (1.0 - y / GC::c) * (1.0 + y / GC::d);
  const double ax = GC::a * x / r, ay = GC::a * y / r;
  const double eta =
      psi / ((1.0 - ax / GC::b) * (1.0 + ax / GC::b) * (1.0 - ay / GC::c) * (1.0 + ay / GC::d));
  const double ring_offset = r / GC::a - 1.0;
  const double alpha = ring_offset * psi;
  const double beta = GreatCourtBeta(x, y, r);

  const double cos_2theta = std::cos(2.0 * theta), sin_theta = std::sin(theta);
  const double east = 0.5 * (1.0 + cos_2theta);
  const double north = 0.5 * (0.5 * (1.0 - cos_2theta) + sin_theta);
  const double south = 0.5 * (0.5 * (1.0 - cos_2theta) - sin_theta);
  const double lambda = kGreatCourtLambda, mu = kGreatCourtMu;

  const double z1 = (GC::h_cen - GC::h_edge) * eta + GC::h_edge;
  const double z2 = alpha * ((1.0 - lambda) * ((35.0 + 10.0 * psi) * east + 24.0 * north +
                                               (7.5 + 12.0 * psi) * 2.0 * south - 1.6) -
                             10.0 * east + 10.0 * north * north * (1.0 - 3.0 * alpha) +
                             2.5 * south * south * ring_offset * ring_offset);
  const double corner_decay =
      (std::exp(-mu * (1.0 - x / GC::b)) + std::exp(-mu * (1.0 + x / GC::b))) *
      (std::exp(-mu * (1.0 - y / GC::c)) + std::exp(-mu * (1.0 + y / GC::d)));
  const double z3 =
      beta * (lambda * (3.5 * east + 3.0 * (1.0 - east) + 0.3 * sin_theta) + 1.05 * corner_decay);
  return z1 + z2 + z3;
}

const std::vector<std::string>& GeneratorNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const Generator& generator : Generators()) list.push_back(generator.name);
    return list;
  }();
  return names;
}

Status MeshHeightField(const HeightField& field, double edge_length, TriMesh* mesh, bool guard_angles) {
  PlanarTriangulation plan;
  PQ_RETURN_IF_ERROR(MeshPlanarDomain(field.domain, edge_length, &plan));
  LiftToMesh(plan, field, mesh);
  constexpr size_t kLatticePlan = 200000;  // planar_domain_mesher.cc's kLatticeAbove
  RemeshOnSurface(field, edge_length, guard_angles, plan.triangles.size() > kLatticePlan ? 2 : 5, mesh);
  mesh->update_face_normals();
  return Status::Ok();
}

Status GenerateSurface(const GeneratorParams& params, TriMesh* mesh) {
  const Generator* generator = FindGenerator(params.name);
  if (generator == nullptr) {
    return Status::InvalidInput("surface.generator '" + params.name +
                                "' is unknown; expected one of " + JoinedNames());
  }
  PQ_RETURN_IF_ERROR(RequirePositive(params.edge_length, "surface.edge_length"));
  HeightField field;
  PQ_RETURN_IF_ERROR(generator->build(params, &field));
  // A domain loop with segments much shorter than the edge (an opening drawn as a circle,
  // geometry/roof_generators.cc) grades the plan mesh: the smoothing then guards the angles.
  // Every other generator's mesh stays as it was (the Great Court's reference, which every
  // golden number rests on, byte-identical).
  constexpr double kGradedSegment = 0.75;
  bool graded = false;
  for (const DomainLoop& loop : field.domain)
    for (size_t k = 0; k < loop.polygon.size(); ++k)
      graded |= (loop.polygon[(k + 1) % loop.polygon.size()] - loop.polygon[k]).norm() < kGradedSegment * params.edge_length;
  return MeshHeightField(field, params.edge_length, mesh, graded).WithContext("surface.edge_length");
}

}  // namespace pqlayout
