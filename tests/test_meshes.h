// Small meshes generated in code for the tests, and helpers to write files into a fresh
// temporary folder.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/mesh.h"
#include "geometry/mesh_io.h"
#include "geometry/surface_generators.h"
#include "geometry/surface_model.h"

namespace pqlayout::testing {

// A fresh empty folder under the system temp dir, unique to the running test.
inline std::string TempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::temp_directory_path() /
                   ("pqlayout_test_" + std::string(info->test_suite_name()) + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline std::string WriteFile(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// An n by n grid of unit squares on [0, n]², each split into two triangles, z = height(x, y).
template <typename Height>
PolygonSoup GridSoup(int n, Height height) {
  PolygonSoup soup;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) soup.points.emplace_back(i, j, height(double(i), double(j)));
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      soup.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return soup;
}

inline PolygonSoup FlatGridSoup(int n) {
  return GridSoup(n, [](double, double) { return 0.0; });
}

inline TriMesh ToMesh(const PolygonSoup& soup) {
  TriMesh mesh;
  EXPECT_TRUE(BuildTriMesh(soup, &mesh, nullptr).ok());
  return mesh;
}

// A built-in surface (see GeneratorParams for the meaning of width, depth and rise).
inline TriMesh GeneratedMesh(const std::string& name, double width, double depth, double rise, double edge) {
  GeneratorParams p;
  p.name = name;
  p.width = width;
  p.depth = depth;
  p.rise = rise;
  p.edge_length = edge;
  TriMesh mesh;
  const Status s = GenerateSurface(p, &mesh);
  EXPECT_TRUE(s.ok()) << s.message();
  return mesh;
}

// The soup as OBJ text (1-based indices, full precision).
inline std::string ObjText(const PolygonSoup& soup) {
  std::ostringstream s;
  s.precision(17);
  for (const auto& p : soup.points) s << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& f : soup.faces) {
    s << "f";
    for (int v : f) s << " " << v + 1;
    s << "\n";
  }
  return s.str();
}

// The interior vertex of s closest to (x, y) in the xy-plane.
inline int ClosestInterior(const SurfaceModel& s, double x, double y) {
  int best = -1;
  double best_d = INFINITY;
  for (int v = 0; v < s.num_vertices(); ++v) {
    if (s.is_boundary(v)) continue;
    const double d = std::hypot(s.position(v).x() - x, s.position(v).y() - y);
    if (d < best_d) best_d = d, best = v;
  }
  return best;
}

// The plan (x, y) of face f's centroid.
inline Eigen::Vector2d Centroid(const SurfaceModel& s, int f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const int v : s.face_vertices(f)) c += s.position(v) / 3.0;
  return c.head<2>();
}

}  // namespace pqlayout::testing
