// Helpers shared by the extraction tests (quad_extraction_test, boundary_refinement_test,
// edge_bracing*_test): flat test meshes, straight level lines, and the checks every extraction must pass.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace extraction_test {

using testing::FlatGridSoup;
using testing::ToMesh;

// A flat grid of m × m squares of side `cell`, each split into two triangles.
inline TriMesh ScaledGrid(int m, double cell) {
  PolygonSoup soup = FlatGridSoup(m);
  for (auto& p : soup.points) p *= cell;
  return ToMesh(soup);
}

// φ, ψ = the coordinates rotated by `angle`, over h, plus offsets.
inline void RotatedCoordinates(const SurfaceModel& s, double angle, double h, double offset, std::vector<double>* phi,
                        std::vector<double>* psi) {
  phi->clear();
  psi->clear();
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d p = s.position(v);
    phi->push_back((std::cos(angle) * p.x() + std::sin(angle) * p.y()) / h + offset);
    psi->push_back((-std::sin(angle) * p.x() + std::cos(angle) * p.y()) / h + offset);
  }
}

inline Eigen::Vector3d OriginPosition(const SurfaceModel& s, const QuadMeshVertex& o) {
  const auto ids = s.face_vertices(o.face);
  return o.barycentric[0] * s.position(ids[0]) + o.barycentric[1] * s.position(ids[1]) +
         o.barycentric[2] * s.position(ids[2]);
}

inline void ExpectOriginsReproducePositions(const SurfaceModel& s, const ExtractedMesh& out) {
  ASSERT_EQ(out.origin.size(), out.mesh.n_vertices());
  for (const auto v : out.mesh.vertices()) {
    const QuadMeshVertex& o = out.origin[v.idx()];
    ASSERT_GE(o.face, 0);
    EXPECT_NEAR(o.barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(o.barycentric.minCoeff(), -1e-12);
    EXPECT_LE((OriginPosition(s, o) - ToEigen(out.mesh.point(v))).norm(), 1e-9) << "vertex " << v.idx();
  }
}

// Every face a simple polygon in the xy-plane (flat tests), counter-clockwise like the
// reference, every vertex manifold.
inline void ExpectSimpleCounterClockwiseManifold(const PolyMesh& mesh) {
  for (const auto f : mesh.faces()) {
    std::vector<Eigen::Vector2d> p;
    for (const auto v : mesh.fv_range(f)) p.push_back(ToEigen(mesh.point(v)).head<2>());
    const size_t n = p.size();
    double area = 0.0;
    for (size_t k = 0; k < n; ++k) area += p[k].x() * p[(k + 1) % n].y() - p[(k + 1) % n].x() * p[k].y();
    EXPECT_GT(area, 0.0) << "face " << f.idx();
    const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
    for (size_t a = 0; a < n; ++a)
      for (size_t b = a + 2; b < n; ++b) {
        if (a == 0 && b == n - 1) continue;  // adjacent through the wrap
        const Eigen::Vector2d p1 = p[a], p2 = p[(a + 1) % n], q1 = p[b], q2 = p[(b + 1) % n];
        const bool separated = cross(p2 - p1, q1 - p1) * cross(p2 - p1, q2 - p1) > 0 ||
                               cross(q2 - q1, p1 - q1) * cross(q2 - q1, p2 - q1) > 0;
        EXPECT_TRUE(separated) << "face " << f.idx() << " crosses itself";
      }
  }
  for (const auto v : mesh.vertices()) EXPECT_TRUE(mesh.is_manifold(v)) << "vertex " << v.idx();
}

// A flat regular n-gon of circumradius r as a triangle mesh: a centre vertex and `rings`
// concentric copies of the polygon, each side cut into `cuts` pieces. Its boundary turns by
// 360°/n at each corner and not at all in between.
inline TriMesh PolygonDisk(int n, double r, int rings, int cuts) {
  PolygonSoup soup;
  soup.points.emplace_back(0.0, 0.0, 0.0);
  const int per_ring = n * cuts;
  for (int k = 1; k <= rings; ++k)
    for (int j = 0; j < per_ring; ++j) {
      const double a0 = 2.0 * M_PI * (j / cuts) / n, a1 = 2.0 * M_PI * (j / cuts + 1) / n;
      const double t = double(j % cuts) / cuts, scale = r * k / rings;
      soup.points.emplace_back(scale * ((1 - t) * std::cos(a0) + t * std::cos(a1)),
                               scale * ((1 - t) * std::sin(a0) + t * std::sin(a1)), 0.0);
    }
  const auto id = [&](int k, int j) { return k == 0 ? 0 : 1 + (k - 1) * per_ring + (j % per_ring); };
  for (int j = 0; j < per_ring; ++j) soup.faces.push_back({0, id(1, j), id(1, j + 1)});
  for (int k = 1; k < rings; ++k)
    for (int j = 0; j < per_ring; ++j) {
      soup.faces.push_back({id(k, j), id(k + 1, j), id(k + 1, j + 1)});
      soup.faces.push_back({id(k, j), id(k + 1, j + 1), id(k, j + 1)});
    }
  return ToMesh(soup);
}

struct ExtractionMetricsAndMesh {
  ExtractedMesh out;
  ExtractedMeshMetrics m;
};

// Extracts and checks what every extraction must give: no refused faces, no cells with holes,
// simple counter-clockwise faces on a manifold, origins that reproduce the positions.
inline ExtractionMetricsAndMesh ExtractValid(const SurfaceModel& s, const std::vector<double>& phi,
                                      const std::vector<double>& psi, double min_edge) {
  ExtractionMetricsAndMesh r;
  EXPECT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, min_edge, &r.out).ok());
  EXPECT_EQ(r.out.stats.rejected_faces, 0);
  EXPECT_EQ(r.out.stats.regions_with_holes, 0);
  ExpectSimpleCounterClockwiseManifold(r.out.mesh);
  ExpectOriginsReproducePositions(s, r.out);
  r.m = MeasureExtractedMesh(s, r.out, 30.0);
  return r;
}

// A 3 × 3 polygon grid of parallelograms in z = 0 (vertex (i, j) at (i + shear·j, j), row by
// row, the top row y = 3; face 3j + i), boundary flags set on the outer ring: the free-edge
// bracing tests' mesh.
inline ExtractedMesh QuadGrid3(double shear) {
  ExtractedMesh out;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i <= 3; ++i) {
      v.push_back(out.mesh.add_vertex(ToOpenMesh(Eigen::Vector3d(i + shear * j, j, 0.0))));
      QuadMeshVertex origin;
      origin.on_boundary = i == 0 || j == 0 || i == 3 || j == 3;
      out.origin.push_back(origin);
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int k = 4 * j + i;
      out.mesh.add_face(std::vector<VertexHandle>{v[k], v[k + 1], v[k + 5], v[k + 4]});
    }
  return out;
}

}  // namespace extraction_test
}  // namespace pqlayout
