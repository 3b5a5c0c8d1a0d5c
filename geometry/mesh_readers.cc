// OBJ, OFF and STL readers (PLY is in ply_reader.cc). See mesh_readers.h for what they share.
#include "geometry/mesh_readers.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string_view>
#include <vector>

#include "geometry/text_reader.h"

namespace pqlayout {
namespace {

// Parses words[first..first+2] as a point; false with *problem set if one is not a number.
bool ParsePoint(const std::vector<std::string_view>& words, size_t first, Eigen::Vector3d* p,
                std::string* problem) {
  for (int k = 0; k < 3; ++k) {
    if (!ParseDouble(words[first + k], &(*p)[k])) {
      *problem = Quote(words[first + k]) + " is not a number";
      return false;
    }
  }
  return true;
}

// One corner of an OBJ face ("7", "7/1", "7//3", "-2/1/1") as a 0-based index. Positive
// indices may name a vertex that comes later in the file: the largest one is kept in
// *max_positive and checked once the file has been read.
bool ParseObjCorner(std::string_view corner, int n_points, int* index, long long* max_positive, std::string* problem) {
  long long number = 0;
  if (!ParseInteger(corner.substr(0, corner.find('/')), &number) || number == 0) {
    *problem = Quote(corner) + " is not a vertex index";
    return false;
  }
  if (number > INT_MAX || n_points + number < 0) {
    *problem = NoSuchVertex(number, n_points);
    return false;
  }
  if (number > 0) *max_positive = std::max(*max_positive, number);
  *index = static_cast<int>(number > 0 ? number - 1 : n_points + number);
  return true;
}

// A `v` or `f` statement; other statements carry nothing pqlayout uses.
bool ReadObjStatement(const std::vector<std::string_view>& words, PolygonSoup* soup, long long* max_index,
                      std::string* problem) {
  if (words[0] == "v") {
    if (words.size() < 4) {
      *problem = "a vertex needs three coordinates";
      return false;
    }
    Eigen::Vector3d p;
    if (!ParsePoint(words, 1, &p, problem)) return false;
    soup->points.push_back(p);
  } else if (words[0] == "f") {
    std::vector<int> face(words.size() - 1);
    const int n_points = static_cast<int>(std::min<size_t>(soup->points.size(), INT_MAX));
    for (size_t k = 1; k < words.size(); ++k)
      if (!ParseObjCorner(words[k], n_points, &face[k - 1], max_index, problem)) return false;
    soup->faces.push_back(std::move(face));
  }
  return true;
}

}  // namespace

Status ReadObjSoup(const std::string& path, PolygonSoup* soup) {
  std::string bytes;
  PQ_RETURN_IF_ERROR(ReadFileBytes(path, &bytes));
  LineScanner lines(bytes);
  std::vector<std::string_view> words;
  std::string problem;
  long long max_index = 0;  // the largest positive vertex index, and its line
  int max_index_line = 0;
  for (std::string_view line; lines.Next(&line);) {
    SplitWords(line, &words);
    if (words.empty()) continue;
    const long long before = max_index;
    if (!ReadObjStatement(words, soup, &max_index, &problem)) return LineError(path, lines.line_number(), problem);
    if (max_index > before) max_index_line = lines.line_number();
  }
  if (soup->points.empty() && soup->faces.empty())
    return Status::InvalidInput(path + ": no vertices or faces found (is this an OBJ file?)");
  if (max_index > static_cast<long long>(soup->points.size()))
    return LineError(path, max_index_line, NoSuchVertex(max_index, soup->points.size()));
  return Status::Ok();
}

namespace {

// The words of OFF lines that hold any, comments (from `#`) removed.
class OffLines {
 public:
  explicit OffLines(std::string_view text) : lines_(text) {}
  bool Next(std::vector<std::string_view>* words) {
    for (std::string_view line; lines_.Next(&line);) {
      SplitWords(line.substr(0, line.find('#')), words);
      if (!words->empty()) return true;
    }
    return false;
  }
  int line_number() const { return lines_.line_number(); }
  size_t offset() const { return lines_.offset(); }

 private:
  LineScanner lines_;
};

// The header: the keyword ([ST][C][N]OFF) and the counts "V F [E]", on its line or the next.
Status ReadOffHeader(const std::string& path, size_t file_size, OffLines* lines, long long* n_vertices,
                     long long* n_faces) {
  std::vector<std::string_view> words;
  if (!lines->Next(&words)) return Status::InvalidInput(path + ": the file is empty");
  const std::string_view keyword = words[0];
  const size_t suffix = keyword.size() >= 3 ? keyword.size() - 3 : 0;
  const std::string_view prefix = keyword.substr(0, suffix);
  if (keyword.size() < 3 || keyword.substr(suffix) != "OFF" ||
      prefix.find_first_not_of("STCN4n") != std::string_view::npos)
    return LineError(path, lines->line_number(), "expected the OFF keyword, not " + Quote(keyword) +
                                                     " (is this an OFF file?)");
  if (prefix.find_first_of("4n") != std::string_view::npos)
    return LineError(path, lines->line_number(), Quote(keyword) + ": only three-dimensional OFF is read");
  size_t first = 1;
  if (words.size() > 1 && words[1] == "BINARY")
    return LineError(path, lines->line_number(), "binary OFF is not read (convert it to ASCII OFF or PLY)");
  if (words.size() == 1) {
    if (!lines->Next(&words)) return Status::InvalidInput(path + ": the file ends before the counts line");
    first = 0;
  }
  const std::string where = path + ":" + std::to_string(lines->line_number()) + ": ";
  if (words.size() < first + 2 || !ParseInteger(words[first], n_vertices) ||
      !ParseInteger(words[first + 1], n_faces))
    return Status::InvalidInput(where + "expected the counts 'vertices faces edges'");
  if (*n_vertices < 0 || *n_faces < 0)
    return Status::InvalidInput(where + "negative count (" + std::to_string(*n_vertices) + " vertices, " +
                                std::to_string(*n_faces) + " faces)");
  // A vertex line takes at least 6 bytes ("0 0 0" and its line break), a face line 2.
  const size_t left = file_size - std::min(file_size, lines->offset()) + 1;
  if (!CountFits(*n_vertices, 6, left) || !CountFits(*n_faces, 2, left - 6 * *n_vertices))
    return Status::InvalidInput(where + std::to_string(*n_vertices) + " vertices and " +
                                std::to_string(*n_faces) + " faces cannot fit in the " +
                                std::to_string(file_size) + " bytes of the file");
  return Status::Ok();
}

// "n i1 ... in [colour]": the face's n indices, each naming one of the n_vertices.
bool ReadOffFace(const std::vector<std::string_view>& words, long long n_vertices, std::vector<int>* face,
                 std::string* problem) {
  long long n = 0;
  if (!ParseInteger(words[0], &n) || n < 0) {
    *problem = Quote(words[0]) + " is not a number of corners";
    return false;
  }
  if (n > static_cast<long long>(words.size()) - 1) {
    *problem = "the face has " + std::to_string(n) + " corners but lists " + std::to_string(words.size() - 1) + " indices";
    return false;
  }
  face->resize(n);
  for (long long k = 0; k < n; ++k) {
    long long index = -1;
    if (!ParseInteger(words[k + 1], &index)) {
      *problem = Quote(words[k + 1]) + " is not a vertex index";
      return false;
    }
    if (index < 0 || index >= n_vertices) {
      *problem = NoSuchVertex(index, n_vertices);
      return false;
    }
    (*face)[k] = static_cast<int>(index);
  }
  return true;
}

Status OffEndsEarly(const std::string& path, long long read, long long declared, const char* what) {
  return Status::InvalidInput(path + ": the file ends after " + std::to_string(read) + " of " +
                              std::to_string(declared) + " " + what);
}

}  // namespace

Status ReadOffSoup(const std::string& path, PolygonSoup* soup) {
  std::string bytes;
  PQ_RETURN_IF_ERROR(ReadFileBytes(path, &bytes));
  OffLines lines(bytes);
  long long n_vertices = 0, n_faces = 0;
  PQ_RETURN_IF_ERROR(ReadOffHeader(path, bytes.size(), &lines, &n_vertices, &n_faces));
  soup->points.reserve(n_vertices);
  soup->faces.reserve(n_faces);
  std::vector<std::string_view> words;
  std::string problem;
  for (long long v = 0; v < n_vertices; ++v) {
    if (!lines.Next(&words)) return OffEndsEarly(path, v, n_vertices, "vertices");
    Eigen::Vector3d p;
    if (words.size() < 3)
      return LineError(path, lines.line_number(), "vertex " + std::to_string(v) + " needs three coordinates");
    if (!ParsePoint(words, 0, &p, &problem))
      return LineError(path, lines.line_number(), "vertex " + std::to_string(v) + ": " + problem);
    soup->points.push_back(p);
  }
  for (long long f = 0; f < n_faces; ++f) {
    if (!lines.Next(&words)) return OffEndsEarly(path, f, n_faces, "faces");
    std::vector<int> face;
    if (!ReadOffFace(words, n_vertices, &face, &problem))
      return LineError(path, lines.line_number(), "face " + std::to_string(f) + ": " + problem);
    soup->faces.push_back(std::move(face));
  }
  return Status::Ok();
}

namespace {

// Gives each distinct position one vertex: STL repeats shared corners in every facet.
class StlVertices {
 public:
  explicit StlVertices(PolygonSoup* soup) : soup_(soup) {}
  // The vertex at p (finite: NaN would break the map's ordering).
  int Add(const Eigen::Vector3d& p) {
    const auto [it, added] = ids_.try_emplace({p.x(), p.y(), p.z()}, static_cast<int>(soup_->points.size()));
    if (added) soup_->points.push_back(p);
    return it->second;
  }

 private:
  PolygonSoup* soup_;
  std::map<std::array<double, 3>, int> ids_;
};

uint32_t LittleEndian32(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
  return value;
}

// 80-byte header, uint32 triangle count, then per triangle: normal, three corners (float32 x
// 3 each, little endian) and a 2-byte attribute.
Status ReadBinaryStl(const std::string& path, const std::string& bytes, uint32_t n_triangles, PolygonSoup* soup) {
  soup->single_precision = true;
  StlVertices vertices(soup);
  soup->faces.reserve(n_triangles);
  for (uint32_t t = 0; t < n_triangles; ++t) {
    std::vector<int> face(3);
    for (int corner = 0; corner < 3; ++corner) {
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        const uint32_t bits = LittleEndian32(bytes, 84 + 50 * size_t{t} + 12 * (corner + 1) + 4 * k);
        float value;
        static_assert(sizeof(value) == sizeof(bits));
        std::memcpy(&value, &bits, sizeof(value));
        p[k] = value;
      }
      if (!p.allFinite())
        return Status::InvalidInput(path + ": facet " + std::to_string(t) + " has a non-finite coordinate");
      face[corner] = vertices.Add(p);
    }
    soup->faces.push_back(std::move(face));
  }
  return Status::Ok();
}

// solid NAME / facet normal N / outer loop / vertex X Y Z (three times) / endloop / endfacet /
// ... / endsolid NAME. The normals are not used; several solids are read as one.
Status ReadAsciiStl(const std::string& path, const std::string& bytes, PolygonSoup* soup) {
  StlVertices vertices(soup);
  LineScanner lines(bytes);
  std::vector<std::string_view> words;
  std::vector<int> corners;
  for (std::string_view line; lines.Next(&line);) {
    SplitWords(line, &words);
    if (words.empty()) continue;
    // Messages are only put together on failure: this loop runs for every line of the file.
    const auto error = [&](const std::string& message) {
      return LineError(path, lines.line_number(), "facet " + std::to_string(soup->faces.size()) + message);
    };
    if (words[0] == "vertex") {
      Eigen::Vector3d p;
      std::string problem;
      if (words.size() < 4) return error(": a vertex needs three coordinates");
      if (!ParsePoint(words, 1, &p, &problem)) return error(": " + problem);
      if (!p.allFinite()) return error(" has a non-finite coordinate");
      if (corners.size() == 3) return error(" has more than three vertices");
      corners.push_back(vertices.Add(p));
    } else if (words[0] == "endfacet") {
      if (corners.size() != 3) return error(" has " + std::to_string(corners.size()) + " vertices, not three");
      soup->faces.push_back(corners);
      corners.clear();
    } else if (words[0] != "solid" && words[0] != "facet" && words[0] != "outer" && words[0] != "endloop" &&
               words[0] != "endsolid") {
      return LineError(path, lines.line_number(), "unexpected " + Quote(words[0]) + " in an ASCII STL file");
    }
  }
  if (!corners.empty())
    return Status::InvalidInput(path + ": the file ends inside facet " + std::to_string(soup->faces.size()));
  return Status::Ok();
}

}  // namespace

Status ReadStlSoup(const std::string& path, PolygonSoup* soup) {
  std::string bytes;
  PQ_RETURN_IF_ERROR(ReadFileBytes(path, &bytes));
  // A binary STL's size is fixed by its triangle count; its 80-byte header may well begin with
  // "solid" too, so the size decides first.
  const uint32_t n_triangles = bytes.size() >= 84 ? LittleEndian32(bytes, 80) : 0;
  const uint64_t binary_size = 84 + 50 * uint64_t{n_triangles};
  if (bytes.size() >= 84 && bytes.size() == binary_size) return ReadBinaryStl(path, bytes, n_triangles, soup);
  const size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start != std::string::npos && bytes.compare(start, 5, "solid") == 0) return ReadAsciiStl(path, bytes, soup);
  std::string binary = "the file is too short for a binary STL";
  if (bytes.size() >= 84)
    binary = "for a binary STL, the header's " + std::to_string(n_triangles) + " triangles need " +
             std::to_string(binary_size) + " bytes, the file has " + std::to_string(bytes.size());
  return Status::InvalidInput(path + ": not an ASCII STL (it does not start with 'solid'), and " + binary);
}

}  // namespace pqlayout
