// Quality measures of a triangle mesh, used in the surface stage's report and in tests.
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

}  // namespace pqlayout
