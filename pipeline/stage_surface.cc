// Stage `surface` (SPEC §1): the reference geometry and its supports.
#include <glog/logging.h>

#include "geometry/mesh_io.h"
#include "geometry/mesh_metrics.h"
#include "geometry/surface_generators.h"
#include "pipeline/layout_checks.h"
#include "pipeline/stages.h"

namespace pqlayout {
namespace {

Status LoadOrGenerate(const SurfaceOptions& options, TriMesh* mesh, std::string* source, std::vector<int>* file_vertex) {
  if (!options.file.empty()) {
    *source = options.file;
    return ReadSurfaceMesh(options.file, mesh, options.weld_tolerance, file_vertex);
  }
  GeneratorParams params;
  params.name = options.generator;
  params.edge_length = options.edge_length;
  params.width = options.width;
  params.depth = options.depth;
  params.rise = options.rise;
  *source = "generator " + options.generator;
  // A progress line first: at 0.17 m the Great Court generator runs ~10 s before the next one.
  LOG(INFO) << "surface: generator " << options.generator << " at edge " << options.edge_length
            << " m: meshing the plan, lifting it, remeshing on the surface ...";
  return GenerateSurface(params, mesh);
}

nlohmann::json SupportCounts(const VertexConditions& supports) {
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& c : supports)
    if (c) counts[BoundaryConditionName(*c)] = counts.value(BoundaryConditionName(*c), 0) + 1;
  return counts;
}

}  // namespace

Status RunSurfaceStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  const Config& config = state->config;
  TriMesh mesh;
  std::string source;
  std::vector<int> file_vertex;  // empty for a generated surface
  PQ_RETURN_IF_ERROR(LoadOrGenerate(config.surface, &mesh, &source, &file_vertex));
  state->surface = std::make_unique<SurfaceModel>(std::move(mesh));
  const SurfaceModel& surface = *state->surface;
  PQ_RETURN_IF_ERROR(ResolveBoundaryConditions(config.boundary, surface, config.extract.corner_angle,
                                               &state->supports, file_vertex.empty() ? nullptr : &file_vertex));
  const SurfaceFrame frame = MeasureSurfaceFrame(surface);
  PQ_RETURN_IF_ERROR(CheckSpacingFitsSurface(surface, frame, config.layout, source));

  const TriangleQuality quality = MeasureTriangleQuality(surface.mesh());
  nlohmann::json loops = nlohmann::json::array();
  for (const auto& loop : surface.boundary_loops())
    loops.push_back({{"vertices", loop.vertices.size()}, {"length", loop.length}, {"outer", loop.is_outer}});
  const auto corners = surface.BoundaryCorners(config.extract.corner_angle * M_PI / 180.0);
  *metrics = {
      {"source", source},
      {"n_vertices", surface.num_vertices()},
      {"n_faces", surface.num_faces()},
      {"n_boundary_vertices", surface.num_boundary_vertices()},
      {"boundary_loops", loops},
      {"n_corners", corners.size()},
      {"area", quality.area},
      {"projected_area", quality.projected_area},
      {"bbox_min", {surface.bbox_min().x(), surface.bbox_min().y(), surface.bbox_min().z()}},
      {"bbox_max", {surface.bbox_max().x(), surface.bbox_max().y(), surface.bbox_max().z()}},
      {"edge_length_min", quality.edge_min},
      {"edge_length_mean", quality.edge_mean},
      {"edge_length_max", quality.edge_max},
      {"min_angle_deg", quality.min_angle_deg},
      {"supports", SupportCounts(state->supports)},
      {"facing_angle_deg", frame.facing_angle_deg},
      {"n_parts", frame.parts},
  };
  if (const std::string warning = SurfaceFrameWarning(frame, source); !warning.empty()) LOG(WARNING) << warning;
  LOG(INFO) << "surface: " << source << ": " << surface.num_faces() << " triangles, "
            << surface.num_vertices() << " vertices, area " << quality.area << " m², "
            << surface.boundary_loops().size() << " boundary loop(s)"
            << (frame.parts > 1 ? ", " + std::to_string(frame.parts) + " separate parts" : std::string())
            << ", min angle "
            << quality.min_angle_deg << "°";
  return WriteMesh(surface.mesh(), out->Path("surface.obj"));
}

}  // namespace pqlayout
