#include "geometry/mesh_io.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <glog/logging.h>

#include "geometry/atomic_file.h"
#include "geometry/mesh_validation.h"

namespace pqlayout {
namespace {

using OpenMesh::Vec2f;
using OpenMesh::Vec3d;
using OpenMesh::Vec3f;
using OpenMesh::Vec3uc;
using OpenMesh::Vec4f;
using OpenMesh::Vec4uc;
using OpenMesh::Attributes::StatusInfo;

// Receives what OpenMesh's readers parse and keeps it verbatim as a polygon soup. Every
// attribute other than positions and face corners is ignored.
class SoupImporter : public OpenMesh::IO::BaseImporter {
 public:
  explicit SoupImporter(PolygonSoup* soup) : soup_(soup) {}

  VertexHandle add_vertex(const Vec3f& p) override { return add_vertex(Vec3d(p)); }
  VertexHandle add_vertex(const Vec3d& p) override {
    soup_->points.emplace_back(p[0], p[1], p[2]);
    return VertexHandle(static_cast<int>(soup_->points.size()) - 1);
  }
  VertexHandle add_vertex() override { return add_vertex(Vec3d(0, 0, 0)); }
  FaceHandle add_face(const VHandles& indices) override {
    std::vector<int> face;
    face.reserve(indices.size());
    for (const auto& v : indices) face.push_back(v.idx());
    soup_->faces.push_back(std::move(face));
    return FaceHandle(static_cast<int>(soup_->faces.size()) - 1);
  }
  void set_point(VertexHandle v, const Vec3f& p) override {
    if (v.is_valid() && v.idx() < static_cast<int>(soup_->points.size()))
      soup_->points[v.idx()] = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  size_t n_vertices() const override { return soup_->points.size(); }
  size_t n_faces() const override { return soup_->faces.size(); }
  size_t n_edges() const override { return 0; }

  // Everything below carries no geometry we use.
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_normal(VertexHandle, const Vec3f&) override {}
  void set_normal(VertexHandle, const Vec3d&) override {}
  void set_color(VertexHandle, const Vec3uc&) override {}
  void set_color(VertexHandle, const Vec4uc&) override {}
  void set_color(VertexHandle, const Vec3f&) override {}
  void set_color(VertexHandle, const Vec4f&) override {}
  void set_texcoord(VertexHandle, const Vec2f&) override {}
  void set_status(VertexHandle, const StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const Vec2f&) override {}
  void set_texcoord(VertexHandle, const Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const Vec3f&) override {}
  void set_status(HalfedgeHandle, const StatusInfo&) override {}
  void set_color(EdgeHandle, const Vec3uc&) override {}
  void set_color(EdgeHandle, const Vec4uc&) override {}
  void set_color(EdgeHandle, const Vec3f&) override {}
  void set_color(EdgeHandle, const Vec4f&) override {}
  void set_status(EdgeHandle, const StatusInfo&) override {}
  void set_normal(FaceHandle, const Vec3f&) override {}
  void set_normal(FaceHandle, const Vec3d&) override {}
  void set_color(FaceHandle, const Vec3uc&) override {}
  void set_color(FaceHandle, const Vec4uc&) override {}
  void set_color(FaceHandle, const Vec3f&) override {}
  void set_color(FaceHandle, const Vec4f&) override {}
  void set_status(FaceHandle, const StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  PolygonSoup* soup_;
};

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

// OpenMesh's readers and writers report to omerr/omlog; our own messages replace them.
struct SilenceOpenMesh {
  SilenceOpenMesh() { omerr().disable(); omlog().disable(); omout().disable(); }
  ~SilenceOpenMesh() { omerr().enable(); omlog().enable(); omout().enable(); }
};

// OBJ is read by this small parser rather than OpenMesh's because OpenMesh 9 parses OBJ
// coordinates into floats (≈ 1e-7 relative: 5 µm on a 50 m roof), and OBJ is how roof
// geometry usually arrives from Rhino. Reads `v` and `f` (with v/vt/vn corners and negative
// indices); other statements (vt, vn, g, o, s, usemtl, l, ...) carry nothing we use.
Status ReadObjSoup(const std::string& path, PolygonSoup* soup) {
  std::ifstream in(path);
  if (!in) return Status::InvalidInput(path + ": cannot open file");
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword)) continue;
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    if (keyword == "v") {
      std::string x, y, z;
      if (!(words >> x >> y >> z)) return Status::InvalidInput(where + "a vertex needs three coordinates");
      Eigen::Vector3d p;
      const std::string* text[3] = {&x, &y, &z};
      for (int k = 0; k < 3; ++k) {
        char* end = nullptr;
        p[k] = std::strtod(text[k]->c_str(), &end);
        if (end == text[k]->c_str() || *end != '\0')
          return Status::InvalidInput(where + "'" + *text[k] + "' is not a number");
      }
      soup->points.push_back(p);
    } else if (keyword == "f") {
      std::vector<int> face;
      std::string corner;
      while (words >> corner) {
        char* end = nullptr;
        const long index = std::strtol(corner.c_str(), &end, 10);
        if (end == corner.c_str() || (*end != '\0' && *end != '/') || index == 0)
          return Status::InvalidInput(where + "'" + corner + "' is not a vertex index");
        const long resolved = index > 0 ? index - 1 : static_cast<long>(soup->points.size()) + index;
        if (resolved < 0) return Status::InvalidInput(where + "vertex index " + corner + " points before the first vertex");
        face.push_back(static_cast<int>(resolved));
      }
      soup->faces.push_back(std::move(face));
    }
  }
  if (soup->points.empty() && soup->faces.empty())
    return Status::InvalidInput(path + ": no vertices or faces found (is this an OBJ file?)");
  return Status::Ok();
}

// OBJ and ASCII PLY are written here, not by OpenMesh's writers, which go through single
// precision points. Coordinates keep 17 significant digits (exact double round trip).
template <typename Mesh>
void WriteObj(const Mesh& mesh, std::ostream& out) {
  out << "# pqlayout: " << mesh.n_vertices() << " vertices, " << mesh.n_faces() << " faces\n";
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    out << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  }
  for (const auto f : mesh.faces()) {
    out << "f";
    for (const auto v : mesh.fv_range(f)) out << " " << v.idx() + 1;
    out << "\n";
  }
}

template <typename Mesh>
void WritePly(const Mesh& mesh, std::ostream& out) {
  const bool colors = mesh.has_face_colors();
  out << "ply\nformat ascii 1.0\ncomment pqlayout\nelement vertex " << mesh.n_vertices()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << mesh.n_faces()
      << "\nproperty list uchar int vertex_indices\n";
  if (colors) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out << "end_header\n";
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    out << p[0] << " " << p[1] << " " << p[2] << "\n";
  }
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
Status WriteMeshImpl(const Mesh& mesh, const std::string& path) {
  const std::string ext = LowerExtension(path);
  if (ext != ".obj" && ext != ".ply")
    return Status::Internal(path + ": cannot write meshes of type '" + ext + "' (use .obj or .ply)");
  return WriteFileAtomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.precision(17);
    if (ext == ".obj") WriteObj(mesh, out);
    else WritePly(mesh, out);
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
  SoupImporter importer(soup);
  OpenMesh::IO::Options options;
  bool ok = false;
  {
    SilenceOpenMesh silence;
    ok = OpenMesh::IO::IOManager().read(path, importer, options);
  }
  if (!ok) return Status::InvalidInput(path + ": could not parse the file as " + ext.substr(1));
  return Status::Ok();
}

Status BuildTriMesh(const PolygonSoup& soup, TriMesh* mesh, int* dropped_vertices) {
  std::vector<int> new_index(soup.points.size(), -1);
  for (const auto& face : soup.faces)
    for (const int v : face) new_index[v] = 0;
  *mesh = TriMesh();
  int dropped = 0;
  for (size_t v = 0; v < soup.points.size(); ++v) {
    if (new_index[v] < 0) {
      ++dropped;
      continue;
    }
    new_index[v] = mesh->add_vertex(ToOpenMesh(soup.points[v])).idx();
  }
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    std::vector<VertexHandle> corners;
    for (const int v : soup.faces[f]) corners.emplace_back(new_index[v]);
    if (!mesh->add_face(corners).is_valid())
      return Status::Internal("face " + std::to_string(f) + " could not be added to the mesh");
  }
  mesh->update_face_normals();
  if (dropped_vertices) *dropped_vertices = dropped;
  return Status::Ok();
}

Status ReadSurfaceMesh(const std::string& path, TriMesh* mesh) {
  PolygonSoup soup;
  PQ_RETURN_IF_ERROR(ReadPolygonSoup(path, &soup));
  PQ_RETURN_IF_ERROR(ValidateSurfaceSoup(soup).WithContext(path));
  int dropped = 0;
  PQ_RETURN_IF_ERROR(BuildTriMesh(soup, mesh, &dropped).WithContext(path));
  if (dropped > 0)
    LOG(WARNING) << path << ": ignored " << dropped << " vertices that no face uses";
  return Status::Ok();
}

Status WriteMesh(const TriMesh& mesh, const std::string& path) { return WriteMeshImpl(mesh, path); }
Status WriteMesh(const PolyMesh& mesh, const std::string& path) { return WriteMeshImpl(mesh, path); }

}  // namespace pqlayout
