#include "python/module_arrays.h"

#include <pybind11/numpy.h>

#include <algorithm>

namespace pqlayout::python {
namespace {

namespace py = pybind11;

py::array_t<double> Column(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

// (n, 3) float64 from n points.
template <typename PointOf>
py::array_t<double> Points(size_t n, PointOf point_of) {
  py::array_t<double> array({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto a = array.mutable_unchecked<2>();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = point_of(i);
    for (int k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(i), k) = p[k];
  }
  return array;
}

py::dict SurfaceDict(const SurfaceModel& surface, const Eigen::Vector3d& origin) {
  py::array_t<int64_t> faces({static_cast<py::ssize_t>(surface.num_faces()), py::ssize_t{3}});
  auto f = faces.mutable_unchecked<2>();
  for (int i = 0; i < surface.num_faces(); ++i)
    for (int k = 0; k < 3; ++k) f(i, k) = surface.face_vertices(i)[k];
  py::dict d;
  d["vertices"] = Points(surface.num_vertices(), [&](size_t v) { return Eigen::Vector3d(surface.position(static_cast<int>(v)) + origin); });
  d["faces"] = faces;
  return d;
}

// Points are in the surface file's coordinates (origin: PipelineState::origin), as in the files.
py::dict GridDict(const PolyMesh& mesh, const Eigen::Vector3d& origin) {
  std::vector<int64_t> offsets = {0}, indices;
  for (const auto f : mesh.faces()) {
    for (const auto v : mesh.fv_range(f)) indices.push_back(v.idx());
    offsets.push_back(static_cast<int64_t>(indices.size()));
  }
  py::dict d;
  d["vertices"] = Points(mesh.n_vertices(), [&](size_t v) {
    return Eigen::Vector3d(ToEigen(mesh.point(VertexHandle(static_cast<int>(v)))) + origin);
  });
  d["face_offsets"] = py::array_t<int64_t>(static_cast<py::ssize_t>(offsets.size()), offsets.data());
  d["face_vertices"] = py::array_t<int64_t>(static_cast<py::ssize_t>(indices.size()), indices.data());
  return d;
}

py::dict TableDict(const ColumnTable& table) {
  py::dict d;
  for (const auto& [name, values] : table) d[py::str(name)] = Column(values);
  return d;
}

py::dict FieldsDict(const PipelineState& state, bool membrane, bool guidance, bool levelset) {
  py::dict d;
  if (membrane) d["v_z"] = Column(state.surface->VertexFieldValues("v_z"));
  if (guidance) {
    const GuidanceField& g = state.guidance;
    d["guidance"] = Points(g.direction.size(), [&](size_t f) { return g.direction[f]; });
    d["strain_max"] = Column(g.major);
    d["strain_min"] = Column(g.minor);
    d["weight"] = Column(g.weight);
  }
  if (levelset) {
    d["phi"] = Column(state.levelsets.phi);
    d["psi"] = Column(state.levelsets.psi);
  }
  return d;
}

}  // namespace

py::dict StateToDict(const PipelineState& state, const std::vector<std::string>& completed) {
  const auto ran = [&](const char* stage) { return std::find(completed.begin(), completed.end(), stage) != completed.end(); };
  py::dict d;
  if (!state.surface) return d;
  d["surface"] = SurfaceDict(*state.surface, state.origin);
  d["fields"] = FieldsDict(state, ran("membrane"), ran("guidance"), ran("levelset"));
  if (ran("extract")) d["quads_initial"] = GridDict(state.quads.mesh, state.origin);
  if (ran("planarize")) d["quads_planarized"] = GridDict(state.planarized.mesh, state.origin);
  // quads: the final grid, as quads.obj (planarize writes it, stiffen replaces it).
  if (ran("stiffen")) d["quads"] = GridDict(state.shell.mesh, state.origin);
  else if (ran("planarize")) d["quads"] = GridDict(state.planarized.mesh, state.origin);
  if (ran("analyze")) {
    py::dict analysis;
    analysis["nodes"] = TableDict(state.analysis.nodes);
    analysis["members"] = TableDict(state.analysis.members);
    d["analysis"] = analysis;
  }
  return d;
}

}  // namespace pqlayout::python
