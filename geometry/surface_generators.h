// Built-in reference surfaces for the `surface` stage (surface.generator): the British
// Museum Great Court roof (C. J. K. Williams 2001, formula in SPEC.md) and simple analytic
// test roofs. Each is a height field z = f(x, y) lifted from a quality triangulation of its
// planar domain (MeshPlanarDomain), with faces oriented so that normals point up (+z).
#pragma once

#include <string>
#include <vector>

#include "geometry/mesh.h"
#include "base/status.h"

namespace pqlayout {

// Great Court roof height (SPEC formula, theta = atan2(y, x)); valid for points in the domain
// -b<=x<=b, -d<=y<=c, r>=a; returns exactly h_edge on the rectangle and h_cen on the ring.
double GreatCourtHeight(double x, double y);

// Plan dimensions in metres: ring radius a, rectangle -b<=x<=b, -d<=y<=c; heights on the
// ring (h_cen) and on the rectangle (h_edge).
struct GreatCourtDimensions {
  static constexpr double a = 22.245, b = 36.625, c = 46.025, d = 51.125, h_cen = 20.955,
                          h_edge = 19.71;
};

struct GeneratorParams {
  std::string name;          // great_court | dome | hypar | barrel | disk | annulus | plane
  double edge_length = 1.0;  // target triangle edge length, metres
  double width = 30.0;       // x extent (dome, hypar, barrel, plane); disk/annulus: outer diameter
  double depth = 30.0;       // y extent (dome, hypar, barrel, plane); annulus: inner diameter
  double rise = 5.0;         // height of the crown above the supports (dome, hypar, barrel)
};

// The list of generator names, for error messages and docs.
const std::vector<std::string>& GeneratorNames();

// Builds the triangle mesh; InvalidInput with a message naming the bad parameter
// (surface.generator / surface.edge_length / surface.width / surface.depth / surface.rise) on
// bad input.
Status GenerateSurface(const GeneratorParams& params, TriMesh* mesh);

}  // namespace pqlayout
