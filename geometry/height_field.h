// A built-in surface as a height field: a planar domain (loops[0] the outer boundary, the
// others holes) and z = height(x, y). surface_generators.cc meshes the domain and lifts it;
// the generators (surface_generators.cc, roof_generators.cc) only say what the roof is.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "base/status.h"
#include "geometry/mesh.h"
#include "geometry/planar_domain_mesher.h"
#include "geometry/surface_generators.h"

namespace pqlayout {

struct HeightField {
  std::vector<DomainLoop> domain;
  std::function<double(double, double)> height;
};

// Meshes the domain at edge_length (MeshPlanarDomain), lifts every vertex to z = height(x, y)
// and remeshes on the surface (edge splits, Delaunay flips, tangential smoothing; boundary
// vertices never move), so that edge length and angles hold in space. Counter-clockwise plan
// triangles: normals point up. guard_angles: the smoothing never takes a triangle's smallest
// angle in space below 20° (and below what it was), for plan meshes that grade from short
// boundary segments. MeshPlanarDomain's errors as they are (the caller names its key).
Status MeshHeightField(const HeightField& field, double edge_length, TriMesh* mesh, bool guard_angles = false);

inline Status RequirePositive(double value, const std::string& key) {
  if (std::isfinite(value) && value > 0.0) return Status::Ok();
  return Status::InvalidInput(key + " must be positive and finite, got " + std::to_string(value));
}

// width, depth and rise all positive (the roofs of roof_generators.cc and the analytic ones).
inline Status RequireWidthDepthRise(const GeneratorParams& params) {
  PQ_RETURN_IF_ERROR(RequirePositive(params.width, "surface.width"));
  PQ_RETURN_IF_ERROR(RequirePositive(params.depth, "surface.depth"));
  return RequirePositive(params.rise, "surface.rise");
}

inline DomainLoop Rectangle(double x_min, double x_max, double y_min, double y_max) {
  DomainLoop loop;
  loop.polygon = {{x_min, y_min}, {x_max, y_min}, {x_max, y_max}, {x_min, y_max}};
  return loop;
}

inline DomainLoop CenteredRectangle(const GeneratorParams& params) {
  return Rectangle(-0.5 * params.width, 0.5 * params.width, -0.5 * params.depth, 0.5 * params.depth);
}

}  // namespace pqlayout
