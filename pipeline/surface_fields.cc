#include "pipeline/surface_fields.h"

#include "geometry/field_writers.h"

namespace pqlayout {

Status WriteSurfaceFieldsVtk(const PipelineState& state, OutputFiles* out) {
  SurfaceModel& surface = *state.surface;
  SurfaceFields fields;
  const std::vector<double> v_z = surface.VertexFieldValues("v_z");
  std::vector<Eigen::Vector3d> displacement(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) displacement[v] = Eigen::Vector3d(0.0, 0.0, v_z[v]);
  fields.vertex_scalars = {{"v_z", v_z}};
  fields.vertex_vectors = {{"displacement", displacement}};
  const GuidanceField& g = state.guidance;
  if (!g.direction.empty()) {
    fields.face_vectors = {{"guidance", g.direction}};
    fields.face_scalars = {{"strain_max", g.major}, {"strain_min", g.minor}, {"magnitude", g.magnitude}, {"weight", g.weight}};
  }
  if (!state.levelsets.phi.empty()) {
    fields.vertex_scalars.push_back({"phi", state.levelsets.phi});
    fields.vertex_scalars.push_back({"psi", state.levelsets.psi});
  }
  return WriteFieldsVtk(surface, fields, out->Path("fields.vtk"), state.origin);
}

}  // namespace pqlayout
