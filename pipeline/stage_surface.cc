// Stage `surface` (SPEC §1): the reference geometry and its supports.
#include <glog/logging.h>

#include <memory>

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

// A georeferenced export (national grid or UTM coordinates: a roof 30 m across at 5,000 km)
// left the planarisation's face planes n·x = d ill-conditioned (d ~ 10⁶ |n|): the corpus's
// 24 m dome at (500000, 5000000, 100) planarised with vertices moved 16 m and came out 44 %
// softer. The planes are now measured from their faces (PlanarityResidual), which fixes that
// at its depth; the local frame stays because the other stages (CGAL's meshing, closest
// points, the membrane and frame solves) have not been measured at map coordinates. Such a surface (its bounding box's centre farther from the origin than 10 of its
// diagonals) is moved so that the centre, rounded to whole metres, is the origin; every
// geometry file is written back at the file's coordinates. Returns the shift (zero if none).
Eigen::Vector3d MoveToLocalFrame(TriMesh* mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const auto v : mesh->vertices()) {
    lo = lo.cwiseMin(ToEigen(mesh->point(v)));
    hi = hi.cwiseMax(ToEigen(mesh->point(v)));
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  if (!(centre.cwiseAbs().maxCoeff() > 10.0 * (hi - lo).norm())) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d origin = centre.array().round();
  for (const auto v : mesh->vertices()) mesh->set_point(v, ToOpenMesh(ToEigen(mesh->point(v)) - origin));
  mesh->update_face_normals();
  return origin;
}

// boundary.rules' boxes are in the file's coordinates.
BoundaryOptions InLocalFrame(BoundaryOptions options, const Eigen::Vector3d& origin) {
  for (auto& rule : options.rules) {
    rule.select.box_min -= origin;
    rule.select.box_max -= origin;
  }
  return options;
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
  auto mesh = std::make_unique<TriMesh>();  // handed to the SurfaceModel without a copy
  std::string source;
  std::vector<int> file_vertex;  // empty for a generated surface
  PQ_RETURN_IF_ERROR(LoadOrGenerate(config.surface, mesh.get(), &source, &file_vertex));
  state->origin = MoveToLocalFrame(mesh.get());
  if (!state->origin.isZero())
    LOG(INFO) << "surface: " << source << " is georeferenced: solved in a local frame whose origin is ("
              << state->origin.x() << ", " << state->origin.y() << ", " << state->origin.z()
              << ") in the file's coordinates (stages.surface.origin); the meshes and tables are written in the file's";
  state->surface = std::make_shared<SurfaceModel>(std::move(mesh));
  // The fields the later stages fill (membrane v_z, levelset φ and ψ), created now: the
  // reference's figures are drawn on the background writer while the next stages run.
  state->surface->FreezeFields({"v_z", "phi", "psi"});
  const SurfaceModel& surface = *state->surface;
  PQ_RETURN_IF_ERROR(ResolveBoundaryConditions(InLocalFrame(config.boundary, state->origin), surface,
                                               config.extract.corner_angle, &state->supports,
                                               file_vertex.empty() ? nullptr : &file_vertex));
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
      {"bbox_min", {surface.bbox_min().x() + state->origin.x(), surface.bbox_min().y() + state->origin.y(),
                    surface.bbox_min().z() + state->origin.z()}},
      {"bbox_max", {surface.bbox_max().x() + state->origin.x(), surface.bbox_max().y() + state->origin.y(),
                    surface.bbox_max().z() + state->origin.z()}},
      {"edge_length_min", quality.edge_min},
      {"edge_length_mean", quality.edge_mean},
      {"edge_length_max", quality.edge_max},
      {"min_angle_deg", quality.min_angle_deg},
      {"supports", SupportCounts(state->supports)},
      {"facing_angle_deg", frame.facing_angle_deg},
      {"n_parts", frame.parts},
      {"origin", {state->origin.x(), state->origin.y(), state->origin.z()}},
  };
  if (const std::string warning = SurfaceFrameWarning(frame, source); !warning.empty()) LOG(WARNING) << warning;
  if (const std::string warning = CoarseReferenceWarning(quality.edge_mean, config.layout.spacing, source); !warning.empty())
    LOG(WARNING) << warning;
  LOG(INFO) << "surface: " << source << ": " << surface.num_faces() << " triangles, "
            << surface.num_vertices() << " vertices, area " << quality.area << " m², "
            << surface.boundary_loops().size() << " boundary loop(s)"
            << (frame.parts > 1 ? ", " + std::to_string(frame.parts) + " separate parts" : std::string())
            << ", min angle "
            << quality.min_angle_deg << "°";
  // Gathered, formatted and written on the writer's thread while the stages go on
  // (base/background_writer.h), from the shared reference (read-only from here on).
  out->WriteInBackground([reference = std::shared_ptr<const SurfaceModel>(state->surface),
                          path = out->Path("surface.obj"), origin = state->origin] {
    return WriteObj(CopyTriangles(reference->mesh()), path, origin);
  });
  return Status::Ok();
}

}  // namespace pqlayout
