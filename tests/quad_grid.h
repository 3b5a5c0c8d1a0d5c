// A quad grid as extraction would hand it over (tests/planarize_test.cc, panel_repair_test.cc).
#pragma once

#include "geometry/quad_extraction.h"

namespace pqlayout::testing {

// A quad grid over a reference triangulation of the same rectangle; z = height(x, y).
template <typename Height>
ExtractedMesh QuadGrid(int nx, int ny, double cell, Height height) {
  ExtractedMesh out;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = i * cell, y = j * cell;
      out.mesh.add_vertex({x, y, height(x, y)});
      QuadMeshVertex origin;
      origin.on_boundary = i == 0 || j == 0 || i == nx || j == ny;
      origin.corner = (i == 0 || i == nx) && (j == 0 || j == ny);
      out.origin.push_back(origin);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int v = j * (nx + 1) + i;
      out.mesh.add_face({VertexHandle(v), VertexHandle(v + 1), VertexHandle(v + nx + 2), VertexHandle(v + nx + 1)});
    }
  return out;
}

}  // namespace pqlayout::testing
