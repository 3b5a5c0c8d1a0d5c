#include "geometry/roof_generators.h"

#include <algorithm>
#include <cmath>

namespace pqlayout {
namespace {

constexpr double kPi = 3.14159265358979323846;
// An opening's circle turns by at most 4° per boundary segment: a circle, not a polygon whose
// every vertex the extraction must follow as a kink (extract.boundary_tolerance makes a turn
// above 2·asin(0.01 / 0.2) = 5.7° sharp). At the reference edge alone (0.6 m on a 1.6 m radius:
// 21° per vertex) the panels at the openings got edges of 0.12–0.19 h (issue 17, edge_min_h).
// The plan mesh then grades from these short segments (MeshHeightField guards its angles).
constexpr double kOpeningMaxTurn = 4.0 * kPi / 180.0;

DomainLoop OpeningLoop(const Eigen::Vector2d& centre, double radius, double edge_length) {
  return CircleLoop(centre, radius, std::min(edge_length, radius * kOpeningMaxTurn));
}

// The ellipse with semi-axes (a, b) as a polygon with sides no longer than edge_length.
DomainLoop Ellipse(double a, double b, double edge_length) {
  const double perimeter = kPi * (3.0 * (a + b) - std::sqrt((3.0 * a + b) * (a + 3.0 * b)));  // Ramanujan
  const int n = std::max(16, static_cast<int>(std::ceil(perimeter / edge_length)));
  DomainLoop loop;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * kPi * i / n;
    loop.polygon.emplace_back(a * std::cos(t), b * std::sin(t));
  }
  return loop;
}

// (1 − u²)(1 − v²): 1 at the centre, 0 on the rectangle's sides.
double Bubble(const GeneratorParams& params, double x, double y) {
  const double u = 2.0 * x / params.width, v = 2.0 * y / params.depth;
  return (1.0 - u * u) * (1.0 - v * v);
}

}  // namespace

Status DomeCircular(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireWidthDepthRise(params));
  const double radius = 0.5 * params.width, rise = params.rise;
  field->domain = {CircleLoop(Eigen::Vector2d::Zero(), radius, params.edge_length)};
  field->height = [=](double x, double y) { return rise * (1.0 - (x * x + y * y) / (radius * radius)); };
  return Status::Ok();
}

Status SaddleElliptic(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireWidthDepthRise(params));
  const double a = 0.5 * params.width, b = 0.5 * params.depth, rise = params.rise;
  field->domain = {Ellipse(a, b, params.edge_length)};
  field->height = [=](double x, double y) {
    const double u = x / a, v = y / b;
    return rise * (0.5 * (u * u - v * v) + 0.15 * std::sin(kPi * u) * (1.0 - v * v));
  };
  return Status::Ok();
}

Status Canopy(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireWidthDepthRise(params));
  field->domain = {CenteredRectangle(params)};
  const double half_width = 0.5 * params.width, half_depth = 0.5 * params.depth, rise = params.rise;
  field->height = [=](double x, double y) {
    const double u = x / half_width, v = y / half_depth;
    return rise * (1.0 - u * u) * 0.5 * (1.0 + v);
  };
  return Status::Ok();
}

Status LShape(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireWidthDepthRise(params));
  const double w = params.width, d = params.depth, rise = params.rise;
  DomainLoop loop;
  loop.polygon = {{-0.5 * w, -0.5 * d}, {0.5 * w, -0.5 * d}, {0.5 * w, 0.0},
                  {0.0, 0.0},           {0.0, 0.5 * d},      {-0.5 * w, 0.5 * d}};
  field->domain = {loop};
  field->height = [=](double x, double y) {
    const double p = (x + 0.125 * w) / (0.7 * w), q = (y + 0.125 * d) / (0.7 * d);
    return rise * (1.0 - p * p - q * q);
  };
  return Status::Ok();
}

Status HoleOffCentre(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireWidthDepthRise(params));
  const Eigen::Vector2d centre(0.2 * params.width, 0.1 * params.depth);
  const double r = 0.12 * std::min(params.width, params.depth), rise = params.rise;
  field->domain = {CenteredRectangle(params), OpeningLoop(centre, r, params.edge_length)};
  field->height = [=](double x, double y) {
    const double rho = (Eigen::Vector2d(x, y) - centre).norm(), t = (rho - 1.6 * r) / (0.5 * r);
    return rise * Bubble(params, x, y) * (1.0 + 0.4 * std::exp(-t * t));
  };
  return Status::Ok();
}

Status TwoHoles(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireWidthDepthRise(params));
  const double s = std::min(params.width, params.depth), rise = params.rise;
  field->domain = {CenteredRectangle(params),
                   OpeningLoop({-0.25 * params.width, 0.0}, 0.1 * s, params.edge_length),
                   OpeningLoop({0.25 * params.width, 0.05 * params.depth}, 0.08 * s, params.edge_length)};
  field->height = [=](double x, double y) { return rise * Bubble(params, x, y); };
  return Status::Ok();
}

Status Wavy(const GeneratorParams& params, HeightField* field) {
  PQ_RETURN_IF_ERROR(RequireWidthDepthRise(params));
  field->domain = {CenteredRectangle(params)};
  struct Bump {
    double a, cx, cy, s;  // amplitude (× rise), centre and width (× plan size)
  };
  const Bump bumps[] = {{1.0, -0.2, -0.15, 0.3}, {0.7, 0.25, 0.2, 0.22}, {0.45, 0.15, -0.3, 0.15}};
  const double w = params.width, d = params.depth, rise = params.rise, size = std::min(w, d);
  field->height = [=](double x, double y) {
    double z = 0.0;
    for (const Bump& b : bumps) {
      const double dx = x - b.cx * w, dy = y - b.cy * d, s = b.s * size;
      z += b.a * std::exp(-(dx * dx + dy * dy) / (s * s));
    }
    return rise * z;
  };
  return Status::Ok();
}

}  // namespace pqlayout
