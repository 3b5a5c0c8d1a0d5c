// Colour-map figures of a ~1M-triangle reference (issue 9: ≤ 5 s and ≤ 20 MB). The mesh is
// a structured triangulation of the Great Court's plan (73.25 m × 97.15 m rectangle with the
// Reading Room's 22 m-radius ring cut out) lifted to a dome, built directly with OpenMesh —
// CGAL meshing of 1M faces would take far longer than the figure. Above
// FigureOptions::max_face_polygons faces the figure writers resample the face colours onto
// a 2 px grid (report/figures.h), so time and size depend on the drawing, not the mesh.
// Counters: faces, bytes (size of the SVG written). BM_FieldsVtk1M: fields.vtk of a run on that
// mesh (every field the pipeline writes), issue 19's "large field files written fast".
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

#include "geometry/field_writers.h"
#include "geometry/surface_model.h"
#include "report/figures.h"

namespace pqlayout {
namespace {

constexpr double kWidth = 73.25, kDepth = 97.15, kRingRadius = 22.0;

// Grid of cells `cell` metres wide over the rectangle centred at the origin, two triangles
// per cell, cells whose centre lies inside the ring left out; z a dome of 8 m rise.
TriMesh StructuredGreatCourt(double cell) {
  const int nx = static_cast<int>(std::ceil(kWidth / cell)), ny = static_cast<int>(std::ceil(kDepth / cell));
  TriMesh mesh;
  std::vector<VertexHandle> v;
  v.reserve(static_cast<size_t>(nx + 1) * (ny + 1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = -0.5 * kWidth + kWidth * i / nx, y = -0.5 * kDepth + kDepth * j / ny;
      const double z = 8.0 * std::cos(M_PI * x / kWidth) * std::cos(M_PI * y / kDepth);
      v.push_back(mesh.add_vertex(TriMesh::Point(x, y, z)));
    }
  const auto id = [nx](int i, int j) { return static_cast<size_t>(j) * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double cx = -0.5 * kWidth + kWidth * (i + 0.5) / nx, cy = -0.5 * kDepth + kDepth * (j + 0.5) / ny;
      if (std::hypot(cx, cy) < kRingRadius) continue;
      mesh.add_face(v[id(i, j)], v[id(i + 1, j)], v[id(i + 1, j + 1)]);
      mesh.add_face(v[id(i, j)], v[id(i + 1, j + 1)], v[id(i, j + 1)]);
    }
  mesh.delete_isolated_vertices();
  mesh.garbage_collection();
  return mesh;
}

const SurfaceModel& MillionTriangles() {
  static const auto* surface = new SurfaceModel(StructuredGreatCourt(0.1058));  // ~1.0M triangles
  return *surface;
}

void BM_DisplacementFigure1M(benchmark::State& state) {
  const SurfaceModel& surface = MillionTriangles();
  std::vector<double> v_z(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) v_z[v] = -0.2 * surface.position(v).z() / 8.0;
  const std::string path = (std::filesystem::temp_directory_path() / "figure_benchmark_v.svg").string();
  for (auto _ : state)
    if (!WriteDisplacementFigure(surface, v_z, "v_z, 1M triangles", path).ok()) state.SkipWithError("write failed");
  state.counters["faces"] = surface.num_faces();
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
}
BENCHMARK(BM_DisplacementFigure1M)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GuidanceFigure1M(benchmark::State& state) {
  const SurfaceModel& surface = MillionTriangles();
  const int nf = surface.num_faces();
  std::vector<Eigen::Vector3d> direction(nf);
  std::vector<double> magnitude(nf), weight(nf);
  for (int f = 0; f < nf; ++f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const int v : surface.face_vertices(f)) c += surface.position(v) / 3.0;
    direction[f] = Eigen::Vector3d(-c.y(), c.x(), 0.0);  // circles around the ring
    magnitude[f] = std::hypot(c.x(), c.y());
    weight[f] = magnitude[f] > 30.0 ? 1.0 : 0.0;
  }
  const std::string path = (std::filesystem::temp_directory_path() / "figure_benchmark_g.svg").string();
  for (auto _ : state)
    if (!WriteGuidanceFigure(surface, direction, magnitude, "|ε_max|", weight, "guidance, 1M triangles", path).ok())
      state.SkipWithError("write failed");
  state.counters["faces"] = nf;
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
}
BENCHMARK(BM_GuidanceFigure1M)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FieldsVtk1M(benchmark::State& state) {
  const SurfaceModel& surface = MillionTriangles();
  const int nv = surface.num_vertices(), nf = surface.num_faces();
  SurfaceFields fields;
  std::vector<double> v_z(nv), phi(nv), psi(nv);
  std::vector<Eigen::Vector3d> displacement(nv), direction(nf);
  for (int v = 0; v < nv; ++v) {
    const Eigen::Vector3d p = surface.position(v);
    v_z[v] = -0.2 * p.z() / 8.0, phi[v] = p.x() / 3.0, psi[v] = p.y() / 3.0;
    displacement[v] = Eigen::Vector3d(0.0, 0.0, v_z[v]);
  }
  std::vector<double> major(nf), minor(nf), magnitude(nf), weight(nf);
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d c = surface.position(surface.face_vertices(f)[0]);
    direction[f] = Eigen::Vector3d(-c.y(), c.x(), 0.0).normalized();
    major[f] = 1e-4 * c.x(), minor[f] = -1e-4 * c.y(), magnitude[f] = std::abs(major[f]), weight[f] = f % 7 / 6.0;
  }
  fields.vertex_scalars = {{"v_z", v_z}, {"phi", phi}, {"psi", psi}};
  fields.vertex_vectors = {{"displacement", displacement}};
  fields.face_scalars = {{"strain_max", major}, {"strain_min", minor}, {"magnitude", magnitude}, {"weight", weight}};
  fields.face_vectors = {{"guidance", direction}};
  const std::string path = (std::filesystem::temp_directory_path() / "figure_benchmark_fields.vtk").string();
  for (auto _ : state)
    if (!WriteFieldsVtk(surface, fields, path).ok()) state.SkipWithError("write failed");
  state.counters["faces"] = nf;
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
}
BENCHMARK(BM_FieldsVtk1M)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pqlayout
