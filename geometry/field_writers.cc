#include "geometry/field_writers.h"

#include <initializer_list>
#include <string>

#include "base/atomic_file.h"
#include "base/format_number.h"

namespace pqlayout {
namespace {

constexpr int kDigits = 12;

// " x" for each value, then "\n" (the first without its space).
void AppendRow(std::string* s, std::initializer_list<double> values) {
  bool first = true;
  for (const double x : values) {
    if (!first) s->push_back(' ');
    AppendNumber(s, x, kDigits);
    first = false;
  }
  s->push_back('\n');
}

std::string VtkName(std::string name) {
  for (char& c : name)
    if (c == ' ') c = '_';
  return name;
}

}  // namespace

Status WriteFieldsVtk(const SurfaceModel& surface, const SurfaceFields& fields, const std::string& path,
                      const Eigen::Vector3d& origin) {
  std::string s = "# vtk DataFile Version 3.0\npqlayout reference surface and fields\nASCII\nDATASET POLYDATA\n";
  s += "POINTS " + std::to_string(surface.num_vertices()) + " double\n";
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Eigen::Vector3d p = surface.position(v) + origin;
    AppendRow(&s, {p.x(), p.y(), p.z()});
  }
  s += "POLYGONS " + std::to_string(surface.num_faces()) + " " + std::to_string(4 * surface.num_faces()) + "\n";
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    s += "3 " + std::to_string(ids[0]) + " " + std::to_string(ids[1]) + " " + std::to_string(ids[2]) + "\n";
  }
  auto write_scalars = [&s](const std::string& name, const std::vector<double>& values) {
    s += "SCALARS " + VtkName(name) + " double 1\nLOOKUP_TABLE default\n";
    for (const double x : values) AppendRow(&s, {x});
  };
  auto write_vectors = [&s](const std::string& name, const std::vector<Eigen::Vector3d>& values) {
    s += "VECTORS " + VtkName(name) + " double\n";
    for (const auto& x : values) AppendRow(&s, {x.x(), x.y(), x.z()});
  };
  if (!fields.vertex_scalars.empty() || !fields.vertex_vectors.empty()) {
    s += "POINT_DATA " + std::to_string(surface.num_vertices()) + "\n";
    for (const auto& [name, values] : fields.vertex_scalars) write_scalars(name, values);
    for (const auto& [name, values] : fields.vertex_vectors) write_vectors(name, values);
  }
  if (!fields.face_scalars.empty() || !fields.face_vectors.empty()) {
    s += "CELL_DATA " + std::to_string(surface.num_faces()) + "\n";
    for (const auto& [name, values] : fields.face_scalars) write_scalars(name, values);
    for (const auto& [name, values] : fields.face_vectors) write_vectors(name, values);
  }
  return WriteTextFileAtomically(path, s);
}

Status WriteCsvTable(const std::vector<std::string>& header, const std::vector<const std::vector<double>*>& columns,
                     const std::string& path) {
  std::string s;
  for (size_t c = 0; c < header.size(); ++c) s += (c ? "," : "") + header[c];
  s += "\n";
  const size_t rows = columns.empty() ? 0 : columns[0]->size();
  for (size_t r = 0; r < rows; ++r) {
    s += std::to_string(r);
    for (const auto* column : columns) {
      s += ',';
      AppendNumber(&s, (*column)[r], kDigits);
    }
    s += "\n";
  }
  return WriteTextFileAtomically(path, s);
}

}  // namespace pqlayout
