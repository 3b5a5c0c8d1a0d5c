#include "geometry/mesh_validation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "base/format_number.h"
#include "geometry/soup_edges.h"

namespace pqlayout {
namespace {

std::string Str1(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string Str(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// Faces are triangles of three distinct, existing vertices.
Status CheckFaces(const PolygonSoup& soup) {
  const int nv = static_cast<int>(soup.points.size());
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& face = soup.faces[f];
    const std::string name = "face " + std::to_string(f);
    if (face.size() != 3)
      return Status::InvalidInput(name + " has " + std::to_string(face.size()) +
                                  " vertices: the reference surface must be a mesh of triangles (quads are split when read; "
                                  "triangulate larger polygons)");
    for (const int v : face)
      if (v < 0 || v >= nv) return Status::InvalidInput(name + " references missing vertex " + std::to_string(v));
    if (face[0] == face[1] || face[1] == face[2] || face[2] == face[0])
      return Status::InvalidInput(name + " is degenerate: it uses a vertex twice");
  }
  return Status::Ok();
}

// The vertices the faces use (unused ones are dropped later, with a warning) are finite and
// plausible; returns their bounding box's diagonal.
Status CheckPoints(const PolygonSoup& soup, double* diagonal) {
  std::vector<char> used(soup.points.size(), 0);
  for (const auto& face : soup.faces)
    for (const int v : face) used[v] = 1;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (size_t v = 0; v < soup.points.size(); ++v) {
    if (!used[v]) continue;
    const Eigen::Vector3d& p = soup.points[v];
    if (!p.allFinite())
      return Status::InvalidInput("vertex " + std::to_string(v) + " has a non-finite coordinate " + Str(p));
    if (p.cwiseAbs().maxCoeff() > kMaxSurfaceCoordinate)
      return Status::InvalidInput("vertex " + std::to_string(v) + " is at " + Str(p) + ", more than " +
                                  Str1(kMaxSurfaceCoordinate) + " m from the origin along an axis (coordinates are metres)");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  *diagonal = (hi - lo).norm();
  return Status::Ok();
}

// Zero-area triangles, relative to the size of the used geometry (a far-away unused vertex
// must not make every face "degenerate").
Status CheckAreas(const PolygonSoup& soup, double diagonal) {
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& face = soup.faces[f];
    const Eigen::Vector3d& p0 = soup.points[face[0]];
    const double area = 0.5 * (soup.points[face[1]] - p0).cross(soup.points[face[2]] - p0).norm();
    if (!(area > 1e-12 * diagonal * diagonal))
      return Status::InvalidInput("face " + std::to_string(f) + " is degenerate (zero area): vertices " +
                                  std::to_string(face[0]) + ", " + std::to_string(face[1]) + ", " +
                                  std::to_string(face[2]));
  }
  return Status::Ok();
}

Status CheckDuplicateFaces(const PolygonSoup& soup) {
  std::vector<std::pair<std::array<int, 3>, int>> sorted(soup.faces.size());
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    std::array<int, 3> key{soup.faces[f][0], soup.faces[f][1], soup.faces[f][2]};
    std::sort(key.begin(), key.end());
    sorted[f] = {key, static_cast<int>(f)};
  }
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i].first == sorted[i - 1].first)
      return Status::InvalidInput("faces " + std::to_string(sorted[i - 1].second) + " and " +
                                  std::to_string(sorted[i].second) + " are duplicates");
  }
  return Status::Ok();
}

// Non-manifold edges, orientation, non-manifold vertices and the boundary, from the sorted
// list of edge uses.
Status CheckManifold(const PolygonSoup& soup) {
  const std::vector<EdgeUse> uses = SortedEdgeUses(soup);
  // Corners 3f+k are joined across every interior edge; a vertex whose corners fall into
  // more than one set has more than one fan of triangles: a non-manifold vertex.
  DisjointSets corners(static_cast<int>(3 * soup.faces.size()));
  auto corner = [&](int face, int vertex) {
    const auto& fv = soup.faces[face];
    return 3 * face + static_cast<int>(std::find(fv.begin(), fv.end(), vertex) - fv.begin());
  };
  bool has_boundary = false;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
    const std::string edge = "edge (" + std::to_string(uses[i].lo) + ", " + std::to_string(uses[i].hi) + ")";
    if (j - i > 2) {
      return Status::InvalidInput("non-manifold " + edge + " is shared by " + std::to_string(j - i) +
                                  " faces (" + std::to_string(uses[i].face) + ", " +
                                  std::to_string(uses[i + 1].face) + ", " + std::to_string(uses[i + 2].face) + ")");
    }
    if (j - i == 1) has_boundary = true;
    if (j - i == 2) {
      if (uses[i].forward == uses[i + 1].forward)
        return Status::InvalidInput("faces " + std::to_string(uses[i].face) + " and " +
                                    std::to_string(uses[i + 1].face) + " have opposite orientations across " +
                                    edge + " (inconsistently oriented or non-orientable mesh)");
      for (const int v : {uses[i].lo, uses[i].hi})
        corners.Union(corner(uses[i].face, v), corner(uses[i + 1].face, v));
    }
    i = j;
  }
  std::vector<int> fan_of_vertex(soup.points.size(), -1);
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = soup.faces[f][k];
      const int fan = corners.Find(static_cast<int>(3 * f + k));
      if (fan_of_vertex[v] < 0) fan_of_vertex[v] = fan;
      if (fan_of_vertex[v] != fan)
        return Status::InvalidInput("non-manifold vertex " + std::to_string(v) + " at " + Str(soup.points[v]) +
                                    ": its triangles form more than one fan (parts touching at a point, or a seam "
                                    "left open between welded ends: raise surface.weld_tolerance to the export's "
                                    "tessellation tolerance)");
    }
  }
  if (!has_boundary)
    return Status::InvalidInput("the mesh is closed (it has no boundary), so it cannot be supported");
  return Status::Ok();
}

}  // namespace

Status CheckCoordinatePrecision(const PolygonSoup& soup, std::string* warning) {
  if (!soup.single_precision) return Status::Ok();
  const int nv = static_cast<int>(soup.points.size());
  double largest = 0.0, edges = 0.0;
  long count = 0;
  for (const auto& face : soup.faces) {
    if (face.size() < 3 || std::any_of(face.begin(), face.end(), [nv](int v) { return v < 0 || v >= nv; })) continue;
    for (size_t k = 0; k < face.size(); ++k) {
      const Eigen::Vector3d& p = soup.points[face[k]];
      largest = std::max(largest, p.cwiseAbs().maxCoeff());
      edges += (soup.points[face[(k + 1) % face.size()]] - p).norm();
      ++count;
    }
  }
  if (count == 0 || !std::isfinite(largest) || !(edges > 0.0)) return Status::Ok();
  const float at = static_cast<float>(largest);
  const double spacing = static_cast<double>(std::nextafter(at, INFINITY)) - static_cast<double>(at);
  const double mean_edge = edges / static_cast<double>(count);
  const auto num = ReadableNumber;
  const std::string what = "float32 coordinates " + num(largest) + " m from the origin are " + num(spacing) +
                           " m apart, " + num(100.0 * spacing / mean_edge) + " % of the mean edge (" + num(mean_edge) +
                           " m)";
  if (spacing > 1e-2 * mean_edge)
    return Status::InvalidInput(what + ": the roof's shape is lost; export it near the origin (a local base point) "
                                "or as OBJ or PLY with double coordinates");
  if (spacing > 1e-4 * mean_edge && warning)
    *warning = what + ": export it near the origin or with double coordinates for a faithful shape";
  return Status::Ok();
}

Status CheckSoupFacesAndPoints(const PolygonSoup& soup, double* diagonal) {
  if (soup.faces.empty()) return Status::InvalidInput("the mesh is empty (no faces)");
  PQ_RETURN_IF_ERROR(CheckFaces(soup));
  return CheckPoints(soup, diagonal);
}

Status ValidateSurfaceSoup(const PolygonSoup& soup) {
  double diagonal = 0.0;
  PQ_RETURN_IF_ERROR(CheckSoupFacesAndPoints(soup, &diagonal));
  PQ_RETURN_IF_ERROR(CheckAreas(soup, diagonal));
  PQ_RETURN_IF_ERROR(CheckDuplicateFaces(soup));
  return CheckManifold(soup);
}

}  // namespace pqlayout
