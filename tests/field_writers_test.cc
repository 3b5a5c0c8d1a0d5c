// fields.vtk (geometry/field_writers.h): legacy VTK polydata, BINARY. Read back here by the
// format's own rules (text headers, big-endian doubles and 32-bit ints, one newline after each
// data block), every value must come back bit for bit and every block at its declared size.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/field_writers.h"
#include "test_meshes.h"

namespace pqlayout {
namespace {

class VtkReader {
 public:
  explicit VtkReader(std::string bytes) : s_(std::move(bytes)) {}
  std::string Line() {
    const size_t end = s_.find('\n', at_);
    EXPECT_NE(end, std::string::npos) << "no line at byte " << at_;
    std::string line = s_.substr(at_, end - at_);
    at_ = end + 1;
    return line;
  }
  template <typename T>
  T Next() {
    EXPECT_LE(at_ + sizeof(T), s_.size());
    char bytes[sizeof(T)];
    for (size_t k = 0; k < sizeof(T); ++k) bytes[k] = s_[at_ + sizeof(T) - 1 - k];  // big-endian → little
    at_ += sizeof(T);
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }
  void EndOfBlock() { EXPECT_EQ(Line(), "") << "a data block must end with a newline"; }
  bool AtEnd() const { return at_ == s_.size(); }

 private:
  std::string s_;
  size_t at_ = 0;
};

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(FieldsVtk, BinaryRoundTripIsExact) {
  const SurfaceModel surface(testing::ToMesh(testing::GridSoup(3, [](double x, double y) { return 0.1 * x * y + 1.0 / 3.0; })));
  const Eigen::Vector3d origin(530000.25, 180000.5, 12.0);  // a georeferenced frame's offset
  SurfaceFields fields;
  std::vector<double> v_z(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) v_z[v] = std::sqrt(2.0 + v) * (v % 2 ? -1e-300 : 1e10);
  std::vector<double> weight(surface.num_faces());
  std::vector<Eigen::Vector3d> direction(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) {
    weight[f] = f / 7.0;
    direction[f] = Eigen::Vector3d(std::cos(f), std::sin(f), -0.0);
  }
  fields.vertex_scalars = {{"v_z", v_z}};
  fields.face_scalars = {{"guidance weight", weight}};
  fields.face_vectors = {{"guidance", direction}};
  const std::string path = testing::TempDir() + "/fields.vtk";
  ASSERT_TRUE(WriteFieldsVtk(surface, fields, path, origin).ok());

  VtkReader r(ReadBytes(path));
  EXPECT_EQ(r.Line(), "# vtk DataFile Version 3.0");
  r.Line();  // title
  EXPECT_EQ(r.Line(), "BINARY");
  EXPECT_EQ(r.Line(), "DATASET POLYDATA");
  const int nv = surface.num_vertices(), nf = surface.num_faces();
  EXPECT_EQ(r.Line(), "POINTS " + std::to_string(nv) + " double");
  for (int v = 0; v < nv; ++v)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(r.Next<double>(), surface.position(v)[d] + origin[d]) << v << " " << d;
  r.EndOfBlock();
  EXPECT_EQ(r.Line(), "POLYGONS " + std::to_string(nf) + " " + std::to_string(4 * nf));
  for (int f = 0; f < nf; ++f) {
    EXPECT_EQ(r.Next<std::int32_t>(), 3);
    for (const int id : surface.face_vertices(f)) EXPECT_EQ(r.Next<std::int32_t>(), id) << f;
  }
  r.EndOfBlock();
  EXPECT_EQ(r.Line(), "POINT_DATA " + std::to_string(nv));
  EXPECT_EQ(r.Line(), "SCALARS v_z double 1");
  EXPECT_EQ(r.Line(), "LOOKUP_TABLE default");
  for (int v = 0; v < nv; ++v) EXPECT_EQ(r.Next<double>(), v_z[v]) << v;  // bit for bit, 1e-300 included
  r.EndOfBlock();
  EXPECT_EQ(r.Line(), "CELL_DATA " + std::to_string(nf));
  EXPECT_EQ(r.Line(), "SCALARS guidance_weight double 1");  // VTK names have no spaces
  EXPECT_EQ(r.Line(), "LOOKUP_TABLE default");
  for (int f = 0; f < nf; ++f) EXPECT_EQ(r.Next<double>(), weight[f]) << f;
  r.EndOfBlock();
  EXPECT_EQ(r.Line(), "VECTORS guidance double");
  for (int f = 0; f < nf; ++f)
    for (int d = 0; d < 3; ++d) {
      const double x = r.Next<double>();
      EXPECT_EQ(x, direction[f][d]) << f << " " << d;
      EXPECT_EQ(std::signbit(x), std::signbit(direction[f][d]));  // −0 stays −0
    }
  r.EndOfBlock();
  EXPECT_TRUE(r.AtEnd());
}

}  // namespace
}  // namespace pqlayout
