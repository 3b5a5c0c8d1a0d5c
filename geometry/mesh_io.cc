#include "geometry/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <glog/logging.h>

#include "base/atomic_file.h"
#include "base/format_number.h"
#include "geometry/mesh_readers.h"
#include "geometry/mesh_validation.h"
#include "geometry/soup_repair.h"

namespace pqlayout {
namespace {

std::string LowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string JoinExtensions(const std::vector<std::string>& exts) {
  std::string out;
  for (const auto& e : exts) out += (out.empty() ? "" : ", ") + e;
  return out;
}

// OBJ and ASCII PLY are written here, not by OpenMesh's writers, which go through single
// precision points. Coordinates keep 17 significant digits (exact double round trip).
constexpr int kPointDigits = 17;

// "x y z\n".
template <typename Point>
void WritePoint(const Point& p, const Eigen::Vector3d& origin, std::ostream& out) {
  for (int k = 0; k < 3; ++k) {
    WriteNumber(out, origin[k] == 0.0 ? p[k] : p[k] + origin[k], kPointDigits);  // -0 stays -0
    out.put(k < 2 ? ' ' : '\n');
  }
}

// points: a range of points; for_each_face(visit) calls visit(ids) for each face in order, ids a
// range of its vertices' 0-based indices.
template <typename Points, typename ForEachFace>
void WriteObj(const Points& points, size_t n_faces, const ForEachFace& for_each_face, const Eigen::Vector3d& origin,
              std::ostream& out) {
  out << "# pqlayout: " << points.size() << " vertices, " << n_faces << " faces\n";
  for (const auto& p : points) {
    out << "v ";
    WritePoint(p, origin, out);
  }
  for_each_face([&](const auto& ids) {
    out << "f";
    for (const auto v : ids) out << " " << v + 1;
    out << "\n";
  });
}

template <typename Mesh>
void WriteObj(const Mesh& mesh, const Eigen::Vector3d& origin, std::ostream& out) {
  std::vector<typename Mesh::Point> points;
  points.reserve(mesh.n_vertices());
  for (const auto v : mesh.vertices()) points.push_back(mesh.point(v));
  WriteObj(points, mesh.n_faces(), [&](const auto& visit) {
    std::vector<int> ids;
    for (const auto f : mesh.faces()) {
      ids.clear();
      for (const auto v : mesh.fv_range(f)) ids.push_back(v.idx());
      visit(ids);
    }
  }, origin, out);
}

template <typename Mesh>
void WritePly(const Mesh& mesh, const Eigen::Vector3d& origin, std::ostream& out) {
  const bool colors = mesh.has_face_colors();
  out << "ply\nformat ascii 1.0\ncomment pqlayout\nelement vertex " << mesh.n_vertices()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << mesh.n_faces()
      << "\nproperty list uchar int vertex_indices\n";
  if (colors) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out << "end_header\n";
  for (const auto v : mesh.vertices()) WritePoint(mesh.point(v), origin, out);
  for (const auto f : mesh.faces()) {
    out << mesh.valence(f);
    for (const auto v : mesh.fv_range(f)) out << " " << v.idx();
    if (colors) {
      const auto c = mesh.color(f);
      out << " " << int(c[0]) << " " << int(c[1]) << " " << int(c[2]);
    }
    out << "\n";
  }
}

template <typename Mesh>
Status WriteMeshImpl(const Mesh& mesh, const std::string& path, const Eigen::Vector3d& origin) {
  const std::string ext = LowerExtension(path);
  if (ext != ".obj" && ext != ".ply")
    return Status::Internal(path + ": cannot write meshes of type '" + ext + "' (use .obj or .ply)");
  return WriteFileAtomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (ext == ".obj") WriteObj(mesh, origin, out);
    else WritePly(mesh, origin, out);
    out.close();
    return static_cast<bool>(out);
  });
}

}  // namespace

const std::vector<std::string>& ReadableMeshExtensions() {
  static const std::vector<std::string> kExtensions{".obj", ".ply", ".off", ".stl"};
  return kExtensions;
}

Status ReadPolygonSoup(const std::string& path, PolygonSoup* soup) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return Status::InvalidInput(path + ": file not found");
  if (!fs::is_regular_file(path, ec)) return Status::InvalidInput(path + ": not a regular file");
  const std::string ext = LowerExtension(path);
  const auto& readable = ReadableMeshExtensions();
  if (std::find(readable.begin(), readable.end(), ext) == readable.end()) {
    return Status::InvalidInput(path + ": unsupported mesh format '" + ext + "' (readable: " +
                                JoinExtensions(readable) + ")");
  }
  *soup = PolygonSoup();
  if (ext == ".obj") return ReadObjSoup(path, soup);
  if (ext == ".ply") return ReadPlySoup(path, soup);
  if (ext == ".off") return ReadOffSoup(path, soup);
  return ReadStlSoup(path, soup);
}

Status BuildTriMesh(const PolygonSoup& soup, TriMesh* mesh, std::vector<int>* mesh_vertex_of) {
  std::vector<int> new_index(soup.points.size(), -1);
  for (const auto& face : soup.faces)
    for (const int v : face) new_index[v] = 0;
  *mesh = TriMesh();
  for (size_t v = 0; v < soup.points.size(); ++v)
    if (new_index[v] >= 0) new_index[v] = mesh->add_vertex(ToOpenMesh(soup.points[v])).idx();
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    std::vector<VertexHandle> corners;
    for (const int v : soup.faces[f]) corners.emplace_back(new_index[v]);
    if (!mesh->add_face(corners).is_valid())
      return Status::Internal("face " + std::to_string(f) + " could not be added to the mesh");
  }
  mesh->update_face_normals();
  if (mesh_vertex_of) *mesh_vertex_of = std::move(new_index);
  return Status::Ok();
}

int SplitQuads(PolygonSoup* soup) {
  const int nv = static_cast<int>(soup->points.size());
  std::vector<std::vector<int>> faces;
  faces.reserve(soup->faces.size());
  int split = 0;
  for (auto& face : soup->faces) {
    const bool quad = face.size() == 4 && std::all_of(face.begin(), face.end(), [nv](int v) { return v >= 0 && v < nv; });
    if (!quad) {  // validation names whatever is wrong with it
      faces.push_back(std::move(face));
      continue;
    }
    // A triangle written as a quad with a vertex repeated (1 2 3 3): the triangle.
    for (size_t k = 0; k < 4 && face.size() == 4; ++k)
      if (face[k] == face[(k + 1) % 4]) face.erase(face.begin() + static_cast<long>(k));
    if (face.size() != 4) {
      faces.push_back(std::move(face));
      continue;
    }
    const auto& p = soup->points;
    const bool first = (p[face[0]] - p[face[2]]).squaredNorm() <= (p[face[1]] - p[face[3]]).squaredNorm();
    if (first) {
      faces.push_back({face[0], face[1], face[2]});
      faces.push_back({face[0], face[2], face[3]});
    } else {
      faces.push_back({face[0], face[1], face[3]});
      faces.push_back({face[1], face[2], face[3]});
    }
    ++split;
  }
  soup->faces = std::move(faces);
  return split;
}

Status PrepareSurfaceSoup(const std::string& path, PolygonSoup* soup, double weld_tolerance,
                          std::vector<int>* vertex_of) {
  std::vector<char> used(soup->points.size(), 0);  // before welding leaves vertices unused
  for (const auto& face : soup->faces)
    for (const int v : face)
      if (v >= 0 && v < static_cast<int>(used.size())) used[v] = 1;
  std::string precision_warning;
  PQ_RETURN_IF_ERROR(CheckCoordinatePrecision(*soup, &precision_warning).WithContext(path));
  if (const int split = SplitQuads(soup); split > 0)
    LOG(INFO) << path << ": " << split << " quads split into two triangles along their shorter diagonal";
  const SoupRepairs repairs = RepairSurfaceSoup(soup, weld_tolerance);
  if (const Status valid = ValidateSurfaceSoup(*soup); !valid.ok()) {  // one line if refused, no warnings first
    const double suggested = SuggestWeldTolerance(*soup);
    if (!(suggested > repairs.tolerance)) return valid.WithContext(path);
    std::ostringstream hint;
    hint << std::setprecision(2) << "; boundary vertices lie up to " << suggested << " m off the other side's edges: "
         << "surface.weld_tolerance: " << 1.5 * suggested << " closes those T-junctions";
    return Status::InvalidInput(valid.message() + hint.str()).WithContext(path);
  }
  if (!precision_warning.empty()) LOG(WARNING) << path << ": " << precision_warning;
  if (repairs.welded > 0)
    LOG(WARNING) << path << ": welded " << repairs.welded << " boundary vertices onto others within " << repairs.tolerance
                 << " m (an unwelded seam: the surface was cut open along it)";
  if (repairs.zipped > 0)
    LOG(WARNING) << path << ": closed " << repairs.zipped << " T-junctions (a vertex of one side in the middle of an "
                 << "edge of the other) by splitting the edge's triangle";
  if (repairs.flipped > 0)
    LOG(WARNING) << path << ": " << repairs.flipped << " triangles were oriented against their neighbours (a patch "
                 << "exported flipped): oriented consistently";
  if (repairs.turned_up > 0)
    LOG(INFO) << path << ": " << repairs.turned_up << " part(s) faced down: turned over to face up";
  if (const auto unused = std::count(used.begin(), used.end(), 0); unused > 0)
    LOG(WARNING) << path << ": ignored " << unused << " vertices that no face uses";
  if (vertex_of) *vertex_of = repairs.vertex_of;
  return Status::Ok();
}

Status ReadSurfaceMesh(const std::string& path, TriMesh* mesh, double weld_tolerance, std::vector<int>* file_vertex) {
  PolygonSoup soup;
  PQ_RETURN_IF_ERROR(ReadPolygonSoup(path, &soup));
  std::vector<int> welded_to;
  PQ_RETURN_IF_ERROR(PrepareSurfaceSoup(path, &soup, weld_tolerance, &welded_to));
  std::vector<int> mesh_vertex;
  PQ_RETURN_IF_ERROR(BuildTriMesh(soup, mesh, &mesh_vertex).WithContext(path));
  if (file_vertex) {
    file_vertex->resize(mesh_vertex.size());
    for (size_t v = 0; v < mesh_vertex.size(); ++v)
      (*file_vertex)[v] = mesh_vertex[welded_to.empty() ? v : static_cast<size_t>(welded_to[v])];
  }
  return Status::Ok();
}

Status WriteMesh(const TriMesh& mesh, const std::string& path, const Eigen::Vector3d& origin) {
  return WriteMeshImpl(mesh, path, origin);
}
Status WriteMesh(const PolyMesh& mesh, const std::string& path, const Eigen::Vector3d& origin) {
  return WriteMeshImpl(mesh, path, origin);
}

TriangleArrays CopyTriangles(const TriMesh& mesh) {
  TriangleArrays copy;
  copy.points.reserve(mesh.n_vertices());
  for (const auto v : mesh.vertices()) copy.points.push_back(ToEigen(mesh.point(v)));
  copy.triangles.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {
    std::array<int, 3> ids{};
    int k = 0;
    for (const auto v : mesh.fv_range(f)) ids[k++] = v.idx();
    copy.triangles.push_back(ids);
  }
  return copy;
}

Status WriteObj(const TriangleArrays& mesh, const std::string& path, const Eigen::Vector3d& origin) {
  return WriteFileAtomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    WriteObj(mesh.points, mesh.triangles.size(), [&](const auto& visit) {
      for (const auto& t : mesh.triangles) visit(t);
    }, origin, out);
    out.close();
    return static_cast<bool>(out);
  });
}

}  // namespace pqlayout
