// Stage `planarize` (paper §3.2; Liu et al. 2006; SPEC §6): vertex positions move so that
// every face becomes planar (δ ≤ planarize.target_delta) while the vertices stay on the
// reference surface, boundary vertices on its boundary, corners fixed and the mesh
// polylines fair. Residual terms: problems/residuals/{planarity,closeness,boundary,
// fairness}_residual.h. Rounds: refresh closest points (CGAL AABB tree), solve (Ceres),
// measure δ (geometry/planarity.h, the SPEC definition); until δ_max ≤ target, each round
// multiplies the planarity weight by 4 and the closeness and boundary weights by 2, so that
// planarity wins in the end without the vertices drifting off the reference (raising
// planarity alone left them 0.47 m off on the Great Court, this schedule 0.22 m).
#pragma once

#include <nlohmann/json.hpp>

#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"
#include "problems/config.h"

namespace pqlayout {

struct PlanarizeReport {
  double planarity_max = 0.0, planarity_mean = 0.0;  // δ (SPEC)
  double closeness_max = 0.0, closeness_mean = 0.0;  // distance to the reference mesh, m
  double boundary_deviation = 0.0;                   // boundary vertices to the reference boundary, m
  double max_displacement = 0.0;                     // from the extracted mesh, m
  int rounds = 0;
  nlohmann::json ceres = nlohmann::json::array();    // one summary per round
  nlohmann::json ToJson() const;
};

// Planarises mesh in place (its origin flags: on_boundary, corner).
Status PlanarizeMesh(const SurfaceModel& reference, const PlanarizeOptions& options, double spacing,
                     ExtractedMesh* mesh, PlanarizeReport* report);

// δ of every face of a polygon mesh.
std::vector<double> FacePlanarity(const PolyMesh& mesh);

}  // namespace pqlayout
