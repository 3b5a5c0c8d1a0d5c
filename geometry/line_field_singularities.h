// Singularities of a per-face line field (d ≡ −d), e.g. the sources of the guidance field
// that the paper's Figure 6 shows. Computed in the top view (xy projection), which is
// faithful for roofs that are height fields: the doubled angle 2θ of the projected
// direction is followed around each interior vertex's ring of faces; its winding number w
// gives the index w/2 (±½ for trisectors/wedges, +1 for sources, sinks and centres).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "geometry/surface_model.h"

namespace pqlayout {

struct LineFieldSingularity {
  int vertex = -1;
  double index = 0.0;              // a multiple of ½
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

// Faces whose projected direction is shorter than min_projected_length are skipped
// (their vertices are not examined).
std::vector<LineFieldSingularity> FindLineFieldSingularities(const SurfaceModel& surface,
                                                             const std::vector<Eigen::Vector3d>& direction,
                                                             double min_projected_length = 1e-6);

}  // namespace pqlayout
