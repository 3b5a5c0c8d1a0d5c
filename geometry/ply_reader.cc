// The PLY reader (see mesh_readers.h). The header is read and checked whole before the body:
// its element counts must fit in the bytes after `end_header`, so nothing is allocated from a
// count the file cannot hold, and every element is read with the same loop whether its values
// are ASCII words or binary numbers of either byte order.
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

#include "geometry/mesh_readers.h"
#include "geometry/text_reader.h"

namespace pqlayout {
namespace {

enum class PlyKind { kSigned, kUnsigned, kFloat };

struct PlyType {
  const char* name;
  PlyKind kind;
  int size;  // bytes
};

// The PLY 1.0 type names and their sized synonyms.
bool ParsePlyType(std::string_view name, PlyType* type) {
  static const PlyType kTypes[] = {
      {"char", PlyKind::kSigned, 1},    {"int8", PlyKind::kSigned, 1},    {"uchar", PlyKind::kUnsigned, 1},
      {"uint8", PlyKind::kUnsigned, 1}, {"short", PlyKind::kSigned, 2},   {"int16", PlyKind::kSigned, 2},
      {"ushort", PlyKind::kUnsigned, 2}, {"uint16", PlyKind::kUnsigned, 2}, {"int", PlyKind::kSigned, 4},
      {"int32", PlyKind::kSigned, 4},   {"uint", PlyKind::kUnsigned, 4},  {"uint32", PlyKind::kUnsigned, 4},
      {"float", PlyKind::kFloat, 4},    {"float32", PlyKind::kFloat, 4},  {"double", PlyKind::kFloat, 8},
      {"float64", PlyKind::kFloat, 8}};
  for (const PlyType& t : kTypes) {
    if (name == t.name) {
      *type = t;
      return true;
    }
  }
  return false;
}

// What a property's values become: a vertex coordinate, a face's corners, or nothing.
enum class PlyRole { kSkip, kX, kY, kZ, kFaceCorners };

struct PlyProperty {
  std::string name;
  PlyType type{};           // of the value, or of each list item
  bool is_list = false;
  PlyType count_type{};     // of a list's length
  PlyRole role = PlyRole::kSkip;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  int line = 0;  // of its `element` line
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t body_offset = 0;  // the first byte after the `end_header` line
  int body_line = 0;       // the line number there (ASCII)
};

// "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME".
Status ParsePlyProperty(const std::vector<std::string_view>& words, const std::string& where,
                        PlyProperty* property) {
  property->is_list = words.size() > 1 && words[1] == "list";
  const size_t expected = property->is_list ? 5 : 3;
  if (words.size() != expected)
    return Status::InvalidInput(where + (property->is_list ? "expected 'property list COUNT_TYPE TYPE NAME'"
                                                           : "expected 'property TYPE NAME'"));
  const std::string_view type = words[expected - 2];
  if (!ParsePlyType(type, &property->type)) return Status::InvalidInput(where + "unknown type " + Quote(type));
  if (property->is_list) {
    if (!ParsePlyType(words[2], &property->count_type))
      return Status::InvalidInput(where + "unknown type " + Quote(words[2]));
    if (property->count_type.kind == PlyKind::kFloat)
      return Status::InvalidInput(where + "a list's length must be an integer type, not " + Quote(words[2]));
  }
  property->name = std::string(words.back());
  return Status::Ok();
}

// One header line after "ply": format, element, property or comment.
Status ParsePlyHeaderLine(const std::vector<std::string_view>& words, const std::string& path, int line,
                          bool* has_format, PlyHeader* header) {
  const std::string where = path + ":" + std::to_string(line) + ": ";
  const std::string_view keyword = words[0];
  if (keyword == "comment" || keyword == "obj_info") return Status::Ok();
  if (keyword == "format") {
    if (*has_format) return Status::InvalidInput(where + "a second 'format' line");
    if (words.size() != 3) return Status::InvalidInput(where + "expected 'format FORMAT 1.0'");
    if (words[1] == "ascii") header->format = PlyFormat::kAscii;
    else if (words[1] == "binary_little_endian") header->format = PlyFormat::kBinaryLittleEndian;
    else if (words[1] == "binary_big_endian") header->format = PlyFormat::kBinaryBigEndian;
    else return Status::InvalidInput(where + "unknown format " + Quote(words[1]));
    *has_format = true;
    return Status::Ok();
  }
  if (keyword == "element") {
    PlyElement element;
    if (words.size() != 3 || !ParseInteger(words[2], &element.count) || element.count < 0)
      return Status::InvalidInput(where + "expected 'element NAME COUNT' with a count >= 0");
    element.name = std::string(words[1]);
    element.line = line;
    // Only the two elements that are read must be unique (checking every name against every
    // other would take quadratic time on a header of many elements).
    if (element.name == "vertex" || element.name == "face")
      for (const PlyElement& e : header->elements)
        if (e.name == element.name) return Status::InvalidInput(where + "a second element " + Quote(element.name));
    header->elements.push_back(std::move(element));
    return Status::Ok();
  }
  if (keyword == "property") {
    if (header->elements.empty()) return Status::InvalidInput(where + "'property' before any 'element'");
    PlyProperty property;
    PQ_RETURN_IF_ERROR(ParsePlyProperty(words, where, &property));
    header->elements.back().properties.push_back(std::move(property));
    return Status::Ok();
  }
  return Status::InvalidInput(where + "unknown header keyword " + Quote(keyword));
}

Status ReadPlyHeader(const std::string& path, std::string_view bytes, PlyHeader* header) {
  LineScanner lines(bytes);
  std::vector<std::string_view> words;
  std::string_view line;
  if (!lines.Next(&line) || (SplitWords(line, &words), words.size() != 1 || words[0] != "ply"))
    return Status::InvalidInput(path + ": the first line is not 'ply' (is this a PLY file?)");
  bool has_format = false;
  while (lines.Next(&line)) {
    SplitWords(line, &words);
    if (words.empty()) continue;
    if (words[0] == "end_header") {
      if (!has_format) return LineError(path, lines.line_number(), "'end_header' before the 'format' line");
      header->body_offset = lines.offset();
      header->body_line = lines.line_number() + 1;
      return Status::Ok();
    }
    PQ_RETURN_IF_ERROR(ParsePlyHeaderLine(words, path, lines.line_number(), &has_format, header));
  }
  return Status::InvalidInput(path + ": the header has no 'end_header' line");
}

// Gives the vertex coordinates and the face corners their roles; every other property is
// skipped. The vertex element must have x, y and z; the face element, if any, a list of
// integer vertex indices.
Status AssignPlyRoles(const std::string& path, PlyHeader* header, long long* n_vertices) {
  bool has_vertices = false;
  for (PlyElement& element : header->elements) {
    const std::string where = path + ":" + std::to_string(element.line) + ": element " + Quote(element.name) + ": ";
    if (element.name == "vertex") {
      has_vertices = true;
      *n_vertices = element.count;
      int found = 0;
      for (PlyProperty& p : element.properties) {
        if (p.name != "x" && p.name != "y" && p.name != "z") continue;
        if (p.is_list) return Status::InvalidInput(where + "property " + Quote(p.name) + " is a list");
        p.role = p.name == "x" ? PlyRole::kX : p.name == "y" ? PlyRole::kY : PlyRole::kZ;
        ++found;
      }
      if (found != 3) return Status::InvalidInput(where + "needs exactly one each of properties x, y and z");
    } else if (element.name == "face") {
      PlyProperty* corners = nullptr;
      for (PlyProperty& p : element.properties)
        if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) corners = &p;
      if (!corners) return Status::InvalidInput(where + "has no list property 'vertex_indices'");
      if (corners->type.kind == PlyKind::kFloat)
        return Status::InvalidInput(where + "vertex indices must be of an integer type, not " + corners->type.name);
      corners->role = PlyRole::kFaceCorners;
    }
  }
  if (!has_vertices) return Status::InvalidInput(path + ": the header declares no 'vertex' element");
  return Status::Ok();
}

// Refuses counts that the body cannot hold, so the reader never allocates for them. An item
// takes at least, in binary, the size of each scalar and each list length; in ASCII, a
// character and a separator per value (the file's last value needs no separator).
Status CheckPlyCounts(const std::string& path, const PlyHeader& header, size_t body_size) {
  const bool ascii = header.format == PlyFormat::kAscii;
  size_t left = body_size + (ascii ? 1 : 0);
  for (const PlyElement& element : header.elements) {
    long long item_bytes = 0;
    for (const PlyProperty& p : element.properties)
      item_bytes += ascii ? 2 : (p.is_list ? p.count_type.size : p.type.size);
    if (item_bytes == 0) continue;  // nothing to read, whatever the count
    if (!CountFits(element.count, item_bytes, left))
      return LineError(path, element.line, "element " + Quote(element.name) + " declares " +
                                               std::to_string(element.count) + " items, more than the " +
                                               std::to_string(body_size) + " bytes after the header can hold");
    left -= element.count * item_bytes;
  }
  return Status::Ok();
}

// ASCII values: words separated by blanks or line breaks. Integer types must be integers in
// their type's range.
class PlyAsciiValues {
 public:
  PlyAsciiValues(std::string_view body, int first_line) : words_(body, first_line) {}
  bool Read(const PlyType& type, double* value, std::string* problem) {
    std::string_view word;
    if (!words_.Next(&word)) {
      *problem = "the file ends";
      return false;
    }
    if (type.kind == PlyKind::kFloat) {
      if (ParseDouble(word, value)) return true;
      *problem = Quote(word) + " is not a number";
      return false;
    }
    const int bits = 8 * type.size;
    const long long lowest = type.kind == PlyKind::kSigned ? -(1LL << (bits - 1)) : 0;
    const long long highest = type.kind == PlyKind::kSigned ? (1LL << (bits - 1)) - 1 : (1LL << bits) - 1;
    long long integer = 0;
    if (!ParseInteger(word, &integer) || integer < lowest || integer > highest) {
      *problem = Quote(word) + " is not a " + type.name;
      return false;
    }
    *value = static_cast<double>(integer);
    return true;
  }
  std::string Where(const std::string& path) const { return path + ":" + std::to_string(words_.line_number()); }

 private:
  WordScanner words_;
};

// Binary values of either byte order, decoded without assuming the machine's.
class PlyBinaryValues {
 public:
  PlyBinaryValues(std::string_view body, bool big_endian) : body_(body), big_endian_(big_endian) {}
  bool Read(const PlyType& type, double* value, std::string* problem) {
    const size_t size = type.size;
    if (body_.size() - offset_ < size) {
      *problem = "the file ends";
      return false;
    }
    uint64_t bits = 0;
    for (size_t k = 0; k < size; ++k) {
      const uint64_t byte = static_cast<unsigned char>(body_[offset_ + k]);
      bits |= byte << (8 * (big_endian_ ? size - 1 - k : k));
    }
    offset_ += size;
    *value = Decode(type, bits);
    return true;
  }
  std::string Where(const std::string& path) const { return path; }

 private:
  static double Decode(const PlyType& type, uint64_t bits) {
    if (type.kind == PlyKind::kUnsigned) return static_cast<double>(bits);
    if (type.kind == PlyKind::kSigned) {
      const int64_t sign = int64_t{1} << (8 * type.size - 1);  // sign-extends a 1, 2 or 4-byte integer
      return static_cast<double>(static_cast<int64_t>(bits ^ sign) - sign);
    }
    if (type.size == 8) {
      double d;
      std::memcpy(&d, &bits, sizeof(d));
      return d;
    }
    const uint32_t bits32 = static_cast<uint32_t>(bits);
    float f;
    std::memcpy(&f, &bits32, sizeof(f));
    return f;
  }

  std::string_view body_;
  bool big_endian_;
  size_t offset_ = 0;
};

// Reads one item of an element: the point's coordinates and the face's corners it has roles for.
template <typename Values>
bool ReadPlyItem(const PlyElement& element, long long n_vertices, Values* values, Eigen::Vector3d* point,
                 std::vector<int>* corners, std::string* problem) {
  double value = 0;
  for (const PlyProperty& p : element.properties) {
    if (!p.is_list) {
      if (!values->Read(p.type, &value, problem)) return false;
      if (p.role != PlyRole::kSkip) (*point)[static_cast<int>(p.role) - static_cast<int>(PlyRole::kX)] = value;
      continue;
    }
    double length = 0;
    if (!values->Read(p.count_type, &length, problem)) return false;
    if (length < 0) {
      *problem = "list " + Quote(p.name) + " has a negative length";
      return false;
    }
    // Each value read consumes input, so a long list ends where the file does.
    for (double k = 0; k < length; ++k) {
      if (!values->Read(p.type, &value, problem)) return false;
      if (p.role != PlyRole::kFaceCorners) continue;
      if (value < 0 || value >= static_cast<double>(n_vertices)) {
        *problem = NoSuchVertex(static_cast<long long>(value), n_vertices);
        return false;
      }
      corners->push_back(static_cast<int>(value));
    }
  }
  return true;
}

template <typename Values>
Status ReadPlyBody(const std::string& path, const PlyHeader& header, long long n_vertices, Values* values,
                   PolygonSoup* soup) {
  for (const PlyElement& element : header.elements) {
    if (element.properties.empty()) continue;
    const bool vertex = element.name == "vertex", face = element.name == "face";
    for (long long i = 0; i < element.count; ++i) {
      Eigen::Vector3d point = Eigen::Vector3d::Zero();
      std::vector<int> corners;
      std::string problem;
      if (!ReadPlyItem(element, n_vertices, values, &point, &corners, &problem))
        return Status::InvalidInput(values->Where(path) + ": " + element.name + " " + std::to_string(i) + ": " +
                                    problem);
      if (vertex) soup->points.push_back(point);
      else if (face) soup->faces.push_back(std::move(corners));
    }
  }
  return Status::Ok();
}

}  // namespace

Status ReadPlySoup(const std::string& path, PolygonSoup* soup) {
  std::string bytes;
  PQ_RETURN_IF_ERROR(ReadFileBytes(path, &bytes));
  PlyHeader header;
  PQ_RETURN_IF_ERROR(ReadPlyHeader(path, bytes, &header));
  long long n_vertices = 0;
  PQ_RETURN_IF_ERROR(AssignPlyRoles(path, &header, &n_vertices));
  for (const PlyElement& element : header.elements)
    for (const PlyProperty& p : element.properties)
      if (p.role >= PlyRole::kX && p.role <= PlyRole::kZ && p.type.kind == PlyKind::kFloat && p.type.size == 4 &&
          header.format != PlyFormat::kAscii)
        soup->single_precision = true;
  const std::string_view body = std::string_view(bytes).substr(header.body_offset);
  PQ_RETURN_IF_ERROR(CheckPlyCounts(path, header, body.size()));
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex") soup->points.reserve(element.count);
    if (element.name == "face") soup->faces.reserve(element.count);
  }
  if (header.format == PlyFormat::kAscii) {
    PlyAsciiValues values(body, header.body_line);
    return ReadPlyBody(path, header, n_vertices, &values, soup);
  }
  PlyBinaryValues values(body, header.format == PlyFormat::kBinaryBigEndian);
  return ReadPlyBody(path, header, n_vertices, &values, soup);
}

}  // namespace pqlayout
