#include "geometry/field_writers.h"

#include <sstream>

#include "base/atomic_file.h"

namespace pqlayout {
namespace {

std::string VtkName(std::string name) {
  for (char& c : name)
    if (c == ' ') c = '_';
  return name;
}

}  // namespace

Status WriteFieldsVtk(const SurfaceModel& surface, const SurfaceFields& fields, const std::string& path) {
  std::ostringstream s;
  s.precision(12);
  s << "# vtk DataFile Version 3.0\npqlayout reference surface and fields\nASCII\nDATASET POLYDATA\n";
  s << "POINTS " << surface.num_vertices() << " double\n";
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Eigen::Vector3d p = surface.position(v);
    s << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  s << "POLYGONS " << surface.num_faces() << " " << 4 * surface.num_faces() << "\n";
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    s << "3 " << ids[0] << " " << ids[1] << " " << ids[2] << "\n";
  }
  auto write_scalars = [&s](const std::string& name, const std::vector<double>& values) {
    s << "SCALARS " << VtkName(name) << " double 1\nLOOKUP_TABLE default\n";
    for (const double x : values) s << x << "\n";
  };
  auto write_vectors = [&s](const std::string& name, const std::vector<Eigen::Vector3d>& values) {
    s << "VECTORS " << VtkName(name) << " double\n";
    for (const auto& x : values) s << x.x() << " " << x.y() << " " << x.z() << "\n";
  };
  if (!fields.vertex_scalars.empty() || !fields.vertex_vectors.empty()) {
    s << "POINT_DATA " << surface.num_vertices() << "\n";
    for (const auto& [name, values] : fields.vertex_scalars) write_scalars(name, values);
    for (const auto& [name, values] : fields.vertex_vectors) write_vectors(name, values);
  }
  if (!fields.face_scalars.empty() || !fields.face_vectors.empty()) {
    s << "CELL_DATA " << surface.num_faces() << "\n";
    for (const auto& [name, values] : fields.face_scalars) write_scalars(name, values);
    for (const auto& [name, values] : fields.face_vectors) write_vectors(name, values);
  }
  return WriteTextFileAtomically(path, s.str());
}

Status WriteCsvTable(const std::vector<std::string>& header, const std::vector<const std::vector<double>*>& columns,
                     const std::string& path) {
  std::ostringstream s;
  s.precision(12);
  for (size_t c = 0; c < header.size(); ++c) s << (c ? "," : "") << header[c];
  s << "\n";
  const size_t rows = columns.empty() ? 0 : columns[0]->size();
  for (size_t r = 0; r < rows; ++r) {
    s << r;
    for (const auto* column : columns) s << "," << (*column)[r];
    s << "\n";
  }
  return WriteTextFileAtomically(path, s.str());
}

}  // namespace pqlayout
