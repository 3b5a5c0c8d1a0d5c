// Stage `extract` (paper §3.1 step 3, SPEC §5): the quad-dominant mesh from the level lines
// φ = i, ψ = j of stage `levelset` (geometry/quad_extraction.h). Writes quads_initial.obj and
// quads_initial.ply (per-face planarity δ as colour, viridis, yellow at δ ≥ 0.025, the
// paper's Fig. 8 scale) and reports the mesh's size, shape and planarity before
// planarisation.
#include <glog/logging.h>

#include <algorithm>
#include <cmath>

#include "geometry/boundary_refinement.h"
#include "geometry/cap_fill.h"
#include "geometry/closest_point.h"
#include "geometry/edge_bracing.h"
#include "geometry/mesh_io.h"
#include "geometry/planarity.h"
#include "geometry/quad_extraction.h"
#include "report/svg_canvas.h"
#include "report/figures.h"
#include "pipeline/stages.h"
#include "problems/edge_bracing_choice.h"
#include "problems/grid_frame.h"

namespace pqlayout {
namespace {

constexpr double kDeltaColourScale = 0.025;  // δ at the top of the colour map
// How far (× h, along the boundary) a level line's end may slide to even out boundary chords:
// the last segment of the line then turns by at most ~15°.
constexpr double kBoundarySlide = 0.25;
// A pole's first row of cells within this × h of its cap's rim is merged into the cap.
constexpr double kCapRow = 0.5;

void ColourByPlanarity(PolyMesh* mesh) {
  mesh->request_face_colors();
  for (const auto f : mesh->faces()) {
    std::vector<Eigen::Vector3d> polygon;
    for (const auto v : mesh->fv_range(f)) polygon.push_back(ToEigen(mesh->point(v)));
    const Rgb c = Viridis(PlanarityDelta(polygon) / kDeltaColourScale);
    mesh->set_color(f, PolyMesh::Color(c.r, c.g, c.b));
  }
}

nlohmann::json Histogram(const std::map<int, int>& counts) {
  nlohmann::json histogram = nlohmann::json::object();
  for (const auto& [key, count] : counts) histogram[std::to_string(key)] = count;
  return histogram;
}

nlohmann::json ToJson(const ExtractedMeshMetrics& m, const ExtractionStats& stats, double h) {
  nlohmann::json non_quads = nlohmann::json::array();
  for (const auto& [sides, c] : m.interior_non_quads)
    non_quads.push_back({{"sides", sides}, {"centroid", {c.x(), c.y(), c.z()}}});
  nlohmann::json caps = nlohmann::json::array();
  for (const auto& [sides, c] : m.caps) caps.push_back({{"sides", sides}, {"centroid", {c.x(), c.y(), c.z()}}});
  return {{"n_vertices", m.n_vertices},
          {"n_faces", m.n_faces},
          {"n_edges", m.n_edges},
          {"quad_fraction", m.quad_fraction},
          {"face_sides", Histogram(m.face_sides)},
          {"valence_histogram", Histogram(m.vertex_valence)},
          {"edge_length_min", m.edge_min / h},
          {"edge_length_mean", m.edge_mean / h},
          {"edge_length_max", m.edge_max / h},
          {"edge_lengths_relative_to", "layout.spacing"},
          {"planarity_max", m.planarity_max},
          {"planarity_mean", m.planarity_mean},
          {"boundary_deviation", m.boundary_deviation_edges},
          {"boundary_deviation_vertices", m.boundary_deviation_vertices},
          {"n_corner_vertices", m.n_corner_vertices},
          {"n_reference_corners", m.n_reference_corners},
          {"euler_characteristic", m.euler_characteristic},
          {"boundary_loops", m.boundary_loops},
          {"interior_non_quads", non_quads},
          {"caps", caps},
          {"collapsed_edges", stats.collapsed_edges},
          {"resplit_boundary_pairs", stats.resplit_boundary_pairs},
          {"collapsed_boundary_triangles", stats.collapsed_boundary_triangles},
          {"split_interior_polygons", stats.split_interior_polygons},
          {"centre_vertices", stats.centre_vertices},
          {"split_boundary_polygons", stats.split_boundary_polygons},
          {"refined_boundary_edges", stats.refined_boundary_edges},
          {"slid_boundary_vertices", stats.slid_boundary_vertices},
          {"dropped_boundary_vertices", stats.dropped_boundary_vertices},
          {"dropped_interior_vertices", stats.dropped_interior_vertices},
          {"moved_onto_boundary", stats.moved_onto_boundary},
          {"regions_with_holes", stats.regions_with_holes},
          {"floating_faces", stats.floating_faces},
          {"unmatched_seam_edges", stats.unmatched_seam_edges},
          {"seam_transition_mismatch", stats.seam_transition_mismatch},
          {"rejected_faces", stats.rejected_faces},
          {"braced_quads", stats.braced_quads}};
}

// A mesh extracted on the level-set stage's working mesh (seams on a remeshed reference):
// every vertex moved to the closest point of the reference (boundary vertices: of its
// boundary) and its origin re-expressed in the reference's triangles, as if extracted there.
void OnReference(const SurfaceModel& reference, ExtractedMesh* quads) {
  const ClosestPointQuery& query = reference.closest_points();
  for (const auto v : quads->mesh.vertices()) {
    QuadMeshVertex& origin = quads->origin[v.idx()];
    const SurfacePoint q = PlacedOnReference(query, origin, ToEigen(quads->mesh.point(v)));
    quads->mesh.set_point(v, ToOpenMesh(q.point));
    origin.face = q.element;
    origin.barycentric = TriangleBarycentric(reference, q.element, q.point);
  }
}

std::vector<CapHole> Caps(const LevelSetSolution& levelsets) {
  std::vector<CapHole> caps;
  for (const LevelSetCap& c : levelsets.caps) caps.push_back({c.centre, c.radius});
  return caps;
}

}  // namespace

Status RunExtractStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  const SurfaceModel& surface = *state->surface;
  const ExtractOptions& options = state->config.extract;
  const double h = state->config.layout.spacing;
  ExtractedMesh& quads = state->quads;
  const LevelSetSolution& levelsets = state->levelsets;
  if (levelsets.seams.cut) {  // a branched layout: φ, ψ per vertex of the cut surface
    SeamTransitions seams;
    seams.cut = levelsets.seams.cut.get();
    seams.sign = levelsets.seams.sign;
    for (const double a : levelsets.seams.phi_offset) seams.phi_offset.push_back(static_cast<int>(std::lround(a)));
    for (const double b : levelsets.seams.psi_offset) seams.psi_offset.push_back(static_cast<int>(std::lround(b)));
    const SurfaceModel& cut_surface = levelsets.seams.working ? *levelsets.seams.working : surface;
    PQ_RETURN_IF_ERROR(ExtractQuadMesh(cut_surface, seams, levelsets.phi_cut, levelsets.psi_cut, options.corner_angle,
                                       options.min_edge * h, &quads, true, Caps(levelsets), h,
                                       levelsets.seams.working ? &surface : nullptr));
    quads.stats.caps = FillCaps(Caps(levelsets), h, kCapRow * h, &quads);
    if (levelsets.seams.working) OnReference(surface, &quads);
  } else if (levelsets.working) {  // single-valued, solved on a remeshed (or holed) working mesh
    PQ_RETURN_IF_ERROR(ExtractQuadMesh(*levelsets.working, levelsets.phi_working, levelsets.psi_working,
                                       options.corner_angle, options.min_edge * h, &quads, true, Caps(levelsets), h,
                                       &surface));
    quads.stats.caps = FillCaps(Caps(levelsets), h, kCapRow * h, &quads);
    OnReference(surface, &quads);
  } else {
    PQ_RETURN_IF_ERROR(ExtractQuadMesh(surface, levelsets.phi, levelsets.psi, options.corner_angle,
                                       options.min_edge * h, &quads));
  }
  RefineBoundaryChords(surface, options.boundary_tolerance * h, kBoundarySlide * h,
                       options.min_edge * h, &quads);
  if (options.brace_free_edges == "all") {  // "paying" is decided after stiffen (stage_stiffen.cc)
    const std::vector<bool> free = FreeBoundaryVertices(quads, VertexRestraints(quads, surface, state->supports));
    LOG(INFO) << "extract: " << BraceFreeEdges(free, &quads) << " quads on free edges cut into triangles (extract.brace_free_edges)";
  }
  if (quads.mesh.n_faces() == 0)
    return Status::Internal("extract: no faces (do the level sets φ, ψ cross any integer level?)");
  const ExtractedMeshMetrics m = MeasureExtractedMesh(surface, quads, options.corner_angle);
  *metrics = ToJson(m, quads.stats, h);

  PolyMesh coloured = quads.mesh;
  ColourByPlanarity(&coloured);
  PQ_RETURN_IF_ERROR(WriteMesh(quads.mesh, out->Path("quads_initial.obj"), state->origin));
  PQ_RETURN_IF_ERROR(WriteMesh(coloured, out->Path("quads_initial.ply"), state->origin));

  LOG(INFO) << "extract: " << m.n_vertices << " vertices, " << m.n_faces << " faces, " << 100.0 * m.quad_fraction
            << " % quads (" << m.interior_non_quads.size() << " non-quads off the boundary), edges "
            << m.edge_min / h << "–" << m.edge_max / h << " h (mean " << m.edge_mean / h << "), δ max "
            << m.planarity_max << " mean " << m.planarity_mean << ", corners " << m.n_corner_vertices << "/"
            << m.n_reference_corners << ", " << quads.stats.collapsed_edges << " short edges merged, boundary within "
            << m.boundary_deviation_edges / h << " h (" << quads.stats.refined_boundary_edges << " boundary vertices added)";
  if (quads.stats.rejected_faces > 0 || quads.stats.regions_with_holes > 0 || quads.stats.floating_faces > 0)
    LOG(WARNING) << "extract: " << quads.stats.rejected_faces << " faces refused as non-manifold, "
                 << quads.stats.regions_with_holes << " cells left out because they are not discs, "
                 << quads.stats.floating_faces << " faces dropped that no boundary holds (the level sets fold over: "
                 << levelsets.metrics.foldovers << " fold-overs)";
  return WritePlanarityFigure(surface, quads.mesh, state->config.planarize.target_delta,
                              "Planarity δ of the extracted mesh (before planarisation)",
                              out->Path("figures/planarity_initial.svg"));
}

}  // namespace pqlayout
