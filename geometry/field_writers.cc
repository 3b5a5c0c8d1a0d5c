#include "geometry/field_writers.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "base/atomic_file.h"
#include "base/format_number.h"

namespace pqlayout {
namespace {

constexpr int kDigits = 12;  // the CSV tables' significant digits

std::string VtkName(std::string name) {
  for (char& c : name)
    if (c == ' ') c = '_';
  return name;
}

// Legacy VTK's binary data: big-endian, doubles and 32-bit ints.
template <typename T>
void AppendBigEndian(std::string* s, T value) {
  static_assert(sizeof(T) == 8 || sizeof(T) == 4);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  std::reverse(bytes, bytes + sizeof(T));
#endif
  s->append(bytes, sizeof(T));
}

void AppendVectors(std::string* s, const std::vector<Eigen::Vector3d>& values) {
  for (const auto& x : values)
    for (int d = 0; d < 3; ++d) AppendBigEndian(s, x[d]);
  s->push_back('\n');
}

}  // namespace

Status WriteFieldsVtk(const SurfaceModel& surface, const SurfaceFields& fields, const std::string& path,
                      const Eigen::Vector3d& origin) {
  std::vector<Eigen::Vector3d> points(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) points[v] = surface.position(v) + origin;
  std::vector<std::array<int, 3>> triangles(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) triangles[f] = surface.face_vertices(f);
  return WriteFieldsVtk(points, triangles, fields, path);
}

Status WriteFieldsVtk(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& triangles,
                      const SurfaceFields& fields, const std::string& path) {
  const int nv = static_cast<int>(points.size()), nf = static_cast<int>(triangles.size());
  std::string s = "# vtk DataFile Version 3.0\npqlayout reference surface and fields\nBINARY\nDATASET POLYDATA\n";
  s.reserve(s.size() + 24 * static_cast<size_t>(nv) * (2 + fields.vertex_vectors.size()) +
            16 * static_cast<size_t>(nf) * (2 + fields.face_vectors.size() + fields.face_scalars.size()));
  s += "POINTS " + std::to_string(nv) + " double\n";
  AppendVectors(&s, points);
  s += "POLYGONS " + std::to_string(nf) + " " + std::to_string(4 * nf) + "\n";
  for (int f = 0; f < nf; ++f) {
    AppendBigEndian<std::int32_t>(&s, 3);
    for (const int id : triangles[f]) AppendBigEndian<std::int32_t>(&s, id);
  }
  s.push_back('\n');
  auto write_scalars = [&s](const std::string& name, const std::vector<double>& values) {
    s += "SCALARS " + VtkName(name) + " double 1\nLOOKUP_TABLE default\n";
    for (const double x : values) AppendBigEndian(&s, x);
    s.push_back('\n');
  };
  auto write_vectors = [&s](const std::string& name, const std::vector<Eigen::Vector3d>& values) {
    s += "VECTORS " + VtkName(name) + " double\n";
    AppendVectors(&s, values);
  };
  if (!fields.vertex_scalars.empty() || !fields.vertex_vectors.empty()) {
    s += "POINT_DATA " + std::to_string(nv) + "\n";
    for (const auto& [name, values] : fields.vertex_scalars) write_scalars(name, values);
    for (const auto& [name, values] : fields.vertex_vectors) write_vectors(name, values);
  }
  if (!fields.face_scalars.empty() || !fields.face_vectors.empty()) {
    s += "CELL_DATA " + std::to_string(nf) + "\n";
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
