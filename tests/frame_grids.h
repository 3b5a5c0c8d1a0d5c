// Small quad grids for the frame and stiffen tests, generated in code.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "geometry/mesh.h"
#include "solver/frame_analysis.h"

namespace pqlayout::testing {

// An n × n grid of quads on [0, n·a]², z = rise × bump, vertices jittered by `jitter` (m).
inline PolyMesh QuadGrid(int n, double a, double rise, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PolyMesh mesh;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = i * a, y = j * a, L = n * a;
      const double z = rise * std::sin(M_PI * x / L) * std::sin(M_PI * y / L);
      const bool inside = i > 0 && j > 0 && i < n && j < n;
      const double dx = inside ? jitter * u(rng) : 0.0, dy = inside ? jitter * u(rng) : 0.0, dz = jitter * u(rng);
      v.push_back(mesh.add_vertex({x + dx, y + dy, z + dz}));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int k = j * (n + 1) + i;
      mesh.add_face(std::vector<VertexHandle>{v[k], v[k + 1], v[k + n + 2], v[k + n + 1]});
    }
  return mesh;
}

// Boundary supports of every kind: x = 0 pinned, y = 0 clamped, x = max sliding, y = max free.
inline std::vector<Restraints> MixedSupports(const PolyMesh& mesh, double L) {
  std::vector<Restraints> r(mesh.n_vertices(), Restraints{});
  for (const auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    if (std::abs(p[1] - L) < 1e-9) continue;
    if (std::abs(p[0]) < 1e-9) r[v.idx()] = {true, true, true, false, false, false};
    else if (std::abs(p[1]) < 1e-9) r[v.idx()] = {true, true, true, true, true, true};
    else if (std::abs(p[0] - L) < 1e-9) r[v.idx()] = {false, false, true, false, false, false};
  }
  return r;
}

}  // namespace pqlayout::testing
