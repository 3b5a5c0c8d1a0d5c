// Quality measures of a triangle mesh, used in the surface stage's report and in tests, and the
// panel counts of a polygon mesh.
#pragma once

#include "geometry/mesh.h"

namespace pqlayout {

struct TriangleQuality {
  double min_angle_deg = 0.0;   // smallest interior angle of any triangle
  double edge_min = 0.0;        // edge lengths, metres
  double edge_mean = 0.0;
  double edge_max = 0.0;
  double area = 0.0;            // total surface area, m²
  double projected_area = 0.0;  // area of the projection onto the xy plane, m²
};

TriangleQuality MeasureTriangleQuality(const TriMesh& mesh);

// The faces with `sides` vertices, and the quads' share of all faces (0 for an empty mesh).
int CountFaces(const PolyMesh& mesh, int sides);
double QuadFraction(const PolyMesh& mesh);

}  // namespace pqlayout
