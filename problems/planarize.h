// Stage `planarize` (paper §3.2; Liu et al. 2006; SPEC §6): vertex positions move so that
// every face becomes planar (δ ≤ planarize.target_delta) while the vertices stay on the
// reference surface, boundary vertices on its boundary, corners fixed, the mesh polylines
// fair and the vertices near where the layout put them. Residual terms, one header each in
// problems/residuals/: planarity (auxiliary plane per face), closeness and boundary (exact
// distance to the reference mesh / its boundary polylines, closest point found afresh at every
// evaluation with CGAL's AABB tree), anchor, fairness; surface_chart_manifold.h keeps a vertex
// on the reference as a hard constraint.
//
// Schedule. Rounds of at most 10 Ceres iterations (warm-started), the planarity weight
// ×30 after each, until δ max ≤ target:
//   1. on the surface: every vertex is a point OF the reference mesh (SurfaceManifold: steps
//      in the triangle's plane, retracted onto the mesh), so closeness is exactly 0 however
//      strong planarity gets. This is where a net that is not conjugate slides along the
//      surface until it nearly is; the anchor, raised with closeness (×3 a round), keeps that
//      to about an edge length (left fixed, it let panels 1.25 m wide slide 6.8 edge lengths
//      and fold: planarize.cc, RoundWeights).
//   2. once a round improves δ max by less than half (on a triangle mesh a vertex pinned to
//      the surface can only bend at the triangles' creases, where the solver stalls): the
//      vertices are set free with the closeness and boundary residuals, weights 1e4 × config,
//      ×3 per round (raised at the switch too), and the last few millimetres of planarity are
//      bought with ≤ 2 cm of closeness on the Great Court (≤ 0.006 h).
// A round ends early at the first iterate with δ max ≤ target / 2 and every vertex within
// 0.01 h of the reference (a Ceres iteration callback): on the Great Court the last round
// gets there in 2 of its 10 iterations.
// The earlier schedule (penalty closeness to a closest point refreshed once per round, only
// ×2 per round against planarity's ×4) ended 0.22 m off the reference on the Great Court,
// with 100-iteration rounds: planarity outgrew closeness, and the tangent plane a round was
// linearised on was wrong by the time vertices had slid metres.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"
#include "problems/options.h"

namespace pqlayout {

struct PlanarizeReport {
  double planarity_max = 0.0, planarity_mean = 0.0;  // δ (SPEC)
  double closeness_max = 0.0, closeness_mean = 0.0;  // distance to the reference mesh, m
  double boundary_deviation = 0.0;                   // boundary vertices to the reference boundary, m
  double max_displacement = 0.0;                     // from the extracted mesh, m
  double max_displacement_edges = 0.0;               // ... in mean edge lengths of the extracted mesh
  // What planarity cost the panels' shapes (measured, not prevented: README, planarisation):
  double edge_length_min = 0.0;                      // shortest edge, relative to h
  int edges_below_min_edge = 0;                      // edges now shorter than extract.min_edge × h
  int folded_faces = 0;                              // convex when extracted, now not: a corner
                                                     // turned inside out or the panel folded
  nlohmann::json folded_at = nlohmann::json::array();  // centroids of the first 10 of them
  std::vector<int> folded_face_ids;                  // all of them (figures; not in report.json)
  int closed_edges = 0;                              // edges closed between passes (stage_planarize.cc)
  int passes = 1;                                    // planarisations run
  int darts_cut = 0;                                 // planar quads with a reflex corner cut in two triangles
  int folded_split = 0;                              // folded panels cut into triangles between passes
  int warped_split = 0;                              // quads cut into two triangles before planarisation (planarize.split_warped)
  int n_faces = 0;                                   // of the planarised mesh (after the repair)
  double quad_fraction = 0.0;                        // ... and its share of quads
  int rounds = 0;
  int iterations = 0;                                // Ceres iterations, all rounds
  nlohmann::json ceres = nlohmann::json::array();    // one summary per round
  nlohmann::json ToJson() const;
};

// Planarises mesh in place (its origin flags: on_boundary, corner). The panel-shape metrics
// are left to MeasurePanelShapes.
// shape_reference: per vertex, where the layout put it (the triangles' orientation residual
// holds them the way round they were there); nullptr: the mesh as given.
Status PlanarizeMesh(const SurfaceModel& reference, const PlanarizeOptions& options, double spacing,
                     ExtractedMesh* mesh, PlanarizeReport* report,
                     const std::vector<Eigen::Vector3d>* shape_reference = nullptr);

// The panel-shape metrics of `report` (edge_length_min, edges_below_min_edge, folded_faces,
// folded_at, n_faces, quad_fraction, and max_displacement(_edges) over all passes) of `mesh`
// against its vertex positions `start` (the extracted mesh): a face is folded if every corner turned the same way round its extracted
// polygon's normal there and one no longer does.
void MeasurePanelShapes(const PolyMesh& mesh, const std::vector<Eigen::Vector3d>& start, double spacing,
                        double min_edge, PlanarizeReport* report);

// δ of every face of a polygon mesh.
std::vector<double> FacePlanarity(const PolyMesh& mesh);

}  // namespace pqlayout
