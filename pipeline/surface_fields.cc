#include "pipeline/surface_fields.h"

#include <glog/logging.h>

#include <chrono>
#include <memory>

#include "geometry/field_writers.h"

namespace pqlayout {

void WriteSurfaceFieldsVtkInBackground(const PipelineState& state, OutputFiles* out) {
  // The values copied here; the reference itself is shared (read-only from the surface stage on:
  // SurfaceModel::FreezeFields), its points and triangles gathered on the writer's thread.
  auto fields = std::make_shared<SurfaceFields>();
  fields->vertex_scalars = {{"v_z", state.surface->VertexFieldValues("v_z")}};
  const GuidanceField& g = state.guidance;
  if (!g.direction.empty()) {
    fields->face_vectors = {{"guidance", g.direction}};
    fields->face_scalars = {{"strain_max", g.major}, {"strain_min", g.minor}, {"magnitude", g.magnitude}, {"weight", g.weight}};
  }
  if (!state.levelsets.phi.empty()) {
    fields->vertex_scalars.push_back({"phi", state.levelsets.phi});
    fields->vertex_scalars.push_back({"psi", state.levelsets.psi});
  }
  out->WriteInBackground([fields, reference = std::shared_ptr<const SurfaceModel>(state.surface), origin = state.origin,
                          path = out->Path("fields.vtk")] {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<double>& v_z = fields->vertex_scalars.front().second;
    std::vector<Eigen::Vector3d> displacement(v_z.size());
    for (size_t v = 0; v < v_z.size(); ++v) displacement[v] = Eigen::Vector3d(0.0, 0.0, v_z[v]);
    fields->vertex_vectors = {{"displacement", std::move(displacement)}};
    PQ_RETURN_IF_ERROR(WriteFieldsVtk(*reference, *fields, path, origin));
    LOG(INFO) << "fields.vtk written in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s (in the background)";
    return Status::Ok();
  });
}

}  // namespace pqlayout
