// Robust minima of a per-vertex scalar field by 0-dimensional persistence: vertices are
// swept in increasing order of value and joined to their processed neighbours with
// union–find; when two basins meet, the shallower one dies with persistence
// (meeting value − its minimum). Minima whose persistence exceeds min_persistence are kept,
// so a flat, noisy trough counts once. Used for the sources of the strain guidance field,
// which sit at the extrema of the membrane displacement (paper §3, Figure 6).
#pragma once

#include <vector>

#include "geometry/surface_model.h"

namespace pqlayout {

struct PersistentMinimum {
  int vertex = -1;
  double value = 0.0;
  double persistence = 0.0;  // infinity for the global minimum
};

// Minima of `values` over the mesh's vertices with persistence > min_persistence, deepest
// first. Boundary vertices take part in the sweep but are never reported as minima.
std::vector<PersistentMinimum> PersistentMinima(const SurfaceModel& surface, const std::vector<double>& values,
                                                double min_persistence);

}  // namespace pqlayout
