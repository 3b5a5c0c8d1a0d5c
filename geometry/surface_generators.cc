// Built-in surfaces: each generator is a height field (planar domain + z = f(x, y)); the
// domain is triangulated by MeshPlanarDomain and every vertex lifted to the surface.
#include "geometry/surface_generators.h"

#include <cmath>
#include <functional>
#include <string>

#include "geometry/planar_domain_mesher.h"

namespace pqlayout {
namespace {

using GC = GreatCourtDimensions;
constexpr double kGreatCourtLambda = 0.5;  // λ of the SPEC formula
constexpr double kGreatCourtMu = 14.0;     // μ of the SPEC formula

// A surface z = height(x, y) over a planar domain (loops[0] outer boundary, others holes).
struct HeightField {
  std::vector<DomainLoop> domain;
  std::function<double(double, double)> height;
};

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

DomainLoop Rectangle(double x_min, double x_max, double y_min, double y_max) {
  DomainLoop loop;
  loop.polygon = {{x_min, y_min}, {x_max, y_min}, {x_max, y_max}, {x_min, y_max}};
  return loop;
}

DomainLoop CenteredRectangle(const GeneratorParams& params) {
  return Rectangle(-0.5 * params.width, 0.5 * params.width, -0.5 * params.depth,
                   0.5 * params.depth);
}

Status RequirePositive(double value, const std::string& key) {
  if (std::isfinite(value) && value > 0.0) return Status::Ok();
  return Status::InvalidInput(key + " must be positive and finite, got " +
                              std::to_string(value));
}

Status GreatCourt(const GeneratorParams& params, HeightField* field) {
  field->domain = {Rectangle(-GC::b, GC::b, -GC::d, GC::c),
                   CircleLoop(Eigen::Vector2d::Zero(), GC::a, params.edge_length)};
  field->height = GreatCourtHeight;
  return Status::Ok();
}

Status Dome(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequirePositive(params.width, "surface.width"));
  PQ_RETURN_IF_ERROR(RequirePositive(params.depth, "surface.depth"));
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
  PQ_RETURN_IF_ERROR(RequirePositive(params.width, "surface.width"));
  PQ_RETURN_IF_ERROR(RequirePositive(params.depth, "surface.depth"));
  PQ_RETURN_IF_ERROR(RequirePositive(params.rise, "surface.rise"));
  field->domain = {CenteredRectangle(params)};
  const double scale = params.rise / (0.25 * params.width * params.depth);
  field->height = [=](double x, double y) { return scale * x * y; };
  return Status::Ok();
}

// Circular-arc vault over the x span: radius R = (w²/4 + rise²) / (2 rise), supports at z = 0.
Status Barrel(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequirePositive(params.width, "surface.width"));
  PQ_RETURN_IF_ERROR(RequirePositive(params.depth, "surface.depth"));
  PQ_RETURN_IF_ERROR(RequirePositive(params.rise, "surface.rise"));
  if (params.rise >= 0.5 * params.width) {
    return Status::InvalidInput("surface.rise of a barrel must be less than half of "
                                "surface.width (the arc would not be a height field)");
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
  PQ_RETURN_IF_ERROR(RequirePositive(params.width, "surface.width"));
  PQ_RETURN_IF_ERROR(RequirePositive(params.depth, "surface.depth"));
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
    return Status::InvalidInput("surface.depth (inner diameter of the annulus) must be less "
                                "than surface.width (outer diameter)");
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
  static const std::vector<Generator> generators = {
      {"great_court", GreatCourt}, {"dome", Dome}, {"hypar", Hypar},     {"barrel", Barrel},
      {"disk", Disk},              {"annulus", Annulus}, {"plane", Plane}};
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

// Lifts each planar point to (x, y, height(x, y)); counter-clockwise triangles in the plane
// give faces whose normals point up.
void LiftToMesh(const PlanarTriangulation& plan, const HeightField& field, TriMesh* mesh) {
  mesh->clear();
  std::vector<VertexHandle> vertices;
  vertices.reserve(plan.points.size());
  for (const Eigen::Vector2d& p : plan.points) {
    vertices.push_back(mesh->add_vertex({p.x(), p.y(), field.height(p.x(), p.y())}));
  }
  for (const std::array<int, 3>& t : plan.triangles) {
    mesh->add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  }
  mesh->update_face_normals();
}

}  // namespace

double GreatCourtHeight(double x, double y) {
  const double r = std::hypot(x, y);
  const double theta = std::atan2(y, x);
  const double psi = (1.0 - x / GC::b) * (1.0 + x / GC::b) * (1.0 - y / GC::c) *
                     (1.0 + y / GC::d);
  const double ax = GC::a * x / r, ay = GC::a * y / r;
  const double eta = psi / ((1.0 - ax / GC::b) * (1.0 + ax / GC::b) * (1.0 - ay / GC::c) *
                            (1.0 + ay / GC::d));
  const double alpha = (r / GC::a - 1.0) * psi;
  const double beta = GreatCourtBeta(x, y, r);

  const double cos_2theta = std::cos(2.0 * theta), sin_theta = std::sin(theta);
  const double east = 0.5 * (1.0 + cos_2theta);
  const double north = 0.5 * (0.5 * (1.0 - cos_2theta) + sin_theta);
  const double south = 0.5 * (0.5 * (1.0 - cos_2theta) - sin_theta);
  const double lambda = kGreatCourtLambda, mu = kGreatCourtMu;
  const double ring_offset = r / GC::a - 1.0;

  const double z1 = (GC::h_cen - GC::h_edge) * eta + GC::h_edge;
  const double z2 =
      alpha * ((1.0 - lambda) * ((35.0 + 10.0 * psi) * east + 24.0 * north +
                                 (7.5 + 12.0 * psi) * 2.0 * south - 1.6) -
               10.0 * east + 10.0 * north * north * (1.0 - 3.0 * alpha) +
               2.5 * south * south * ring_offset * ring_offset);
  const double corner_decay =
      (std::exp(-mu * (1.0 - x / GC::b)) + std::exp(-mu * (1.0 + x / GC::b))) *
      (std::exp(-mu * (1.0 - y / GC::c)) + std::exp(-mu * (1.0 + y / GC::d)));
  const double z3 = beta * (lambda * (3.5 * east + 3.0 * (1.0 - east) + 0.3 * sin_theta) +
                            1.05 * corner_decay);
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

Status GenerateSurface(const GeneratorParams& params, TriMesh* mesh) {
  const Generator* generator = FindGenerator(params.name);
  if (generator == nullptr) {
    return Status::InvalidInput("surface.generator '" + params.name +
                                "' is unknown; expected one of " + JoinedNames());
  }
  PQ_RETURN_IF_ERROR(RequirePositive(params.edge_length, "surface.edge_length"));
  HeightField field;
  PQ_RETURN_IF_ERROR(generator->build(params, &field));
  PlanarTriangulation plan;
  PQ_RETURN_IF_ERROR(
      MeshPlanarDomain(field.domain, params.edge_length, &plan).WithContext("surface.edge_length"));
  LiftToMesh(plan, field, mesh);
  return Status::Ok();
}

}  // namespace pqlayout
