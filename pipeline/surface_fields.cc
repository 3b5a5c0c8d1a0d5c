#include "pipeline/surface_fields.h"

#include <glog/logging.h>

#include <chrono>
#include <memory>

#include "geometry/field_writers.h"
#include "geometry/mesh_io.h"

namespace pqlayout {

void WriteSurfaceFieldsVtkInBackground(const PipelineState& state, OutputFiles* out) {
  SurfaceModel& surface = *state.surface;  // VertexFieldValues is not const
  auto fields = std::make_shared<SurfaceFields>();
  const std::vector<double> v_z = surface.VertexFieldValues("v_z");
  std::vector<Eigen::Vector3d> displacement(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) displacement[v] = Eigen::Vector3d(0.0, 0.0, v_z[v]);
  fields->vertex_scalars = {{"v_z", v_z}};
  fields->vertex_vectors = {{"displacement", std::move(displacement)}};
  const GuidanceField& g = state.guidance;
  if (!g.direction.empty()) {
    fields->face_vectors = {{"guidance", g.direction}};
    fields->face_scalars = {{"strain_max", g.major}, {"strain_min", g.minor}, {"magnitude", g.magnitude}, {"weight", g.weight}};
  }
  if (!state.levelsets.phi.empty()) {
    fields->vertex_scalars.push_back({"phi", state.levelsets.phi});
    fields->vertex_scalars.push_back({"psi", state.levelsets.psi});
  }
  auto mesh = std::make_shared<TriangleArrays>(CopyTriangles(surface.mesh()));
  for (Eigen::Vector3d& p : mesh->points) p += state.origin;
  out->WriteInBackground([fields, mesh, path = out->Path("fields.vtk")] {
    const auto start = std::chrono::steady_clock::now();
    PQ_RETURN_IF_ERROR(WriteFieldsVtk(mesh->points, mesh->triangles, *fields, path));
    LOG(INFO) << "fields.vtk written in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s (in the background)";
    return Status::Ok();
  });
}

}  // namespace pqlayout
