// The guidance field (strain, curvature or file): see problems/guidance.h.
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <queue>
#include <sstream>
#include <tuple>

#include "base/parallel_ranges.h"
#include "geometry/differential_operators.h"
#include "geometry/principal_directions.h"
#include "problems/guidance.h"

namespace pqlayout {

std::vector<double> AlignmentWeights(const std::vector<double>& magnitude, double scale, double threshold,
                                     double ramp) {
  std::vector<double> weight(magnitude.size(), 0.0);
  if (!(scale > 0.0)) return weight;
  for (size_t f = 0; f < magnitude.size(); ++f) {
    const double relative = magnitude[f] / scale;
    if (ramp > 0.0) weight[f] = std::clamp((relative - threshold) / ramp, 0.0, 1.0);
    else weight[f] = relative >= threshold ? 1.0 : 0.0;
  }
  return weight;
}

namespace {

void Resize(int faces, GuidanceField* field) {
  field->direction.assign(faces, Eigen::Vector3d::Zero());
  field->major.assign(faces, 0.0);
  field->minor.assign(faces, 0.0);
  field->magnitude.assign(faces, 0.0);
}

// How clearly e_max is the direction to follow, per face: |ε_max|, less |ε_min| where the two
// principal strains have opposite signs (shear_switch = weak). e_max is the eigenvector of
// largest modulus (paper), so across a line where ε_max = −ε_min (pure shear: a hypar's field,
// a saddle's flanks) it swaps to the other eigenvector, a 90° jump that no family of level
// lines can follow; the paper's weight |ε_max| is high there and the solve bent the layout to
// it (corpus strain runs: 7–14 % of the strongly guided area more than 16° off, the worst
// 80–90° at such a swap). This weight vanishes on the line and the fallback fills in. Where
// the principal strains share a sign (a crown, a sag) the paper's weight stays: there e_max
// turns continuously round a true singularity, which the seams handle.
std::vector<double> StrainDominance(const GuidanceField& field, const GuidanceOptions& options) {
  std::vector<double> dominance(field.magnitude);
  if (options.shear_switch != "weak") return dominance;
  for (size_t f = 0; f < dominance.size(); ++f)
    if (field.major[f] * field.minor[f] < 0.0) dominance[f] -= std::abs(field.minor[f]);
  return dominance;
}

// Faces reached along the maximum spanning tree (CombCurvatureNet), each flagged where it
// takes the other family.
std::vector<char> CombingFlips(const SurfaceModel& surface, const GuidanceField& field) {
  const int n = surface.num_faces();
  std::vector<char> reached(n, 0), flip(n, 0);
  using Entry = std::tuple<double, int, int>;  // key, −face (ties: lower index first), parent
  std::vector<int> order(n);
  for (int f = 0; f < n; ++f) order[f] = f;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return field.weight[a] > field.weight[b]; });
  const auto chosen = [&](int f) {
    return flip[f] ? Eigen::Vector3d(surface.face_normal(f).cross(field.direction[f])) : field.direction[f];
  };
  for (const int root : order) {
    if (reached[root]) continue;
    std::priority_queue<Entry> queue;
    queue.push({field.weight[root], -root, -1});
    while (!queue.empty()) {
      const auto [key, minus_g, parent] = queue.top();
      queue.pop();
      const int g = -minus_g;
      if (reached[g]) continue;
      reached[g] = 1;
      if (parent >= 0) {
        const Eigen::Vector3d from = chosen(parent);
        const Eigen::Vector3d across = surface.face_normal(g).cross(field.direction[g]);
        flip[g] = std::abs(from.dot(across)) > std::abs(from.dot(field.direction[g]));
      }
      for (const auto h : surface.mesh().ff_range(FaceHandle(g)))
        if (!reached[h.idx()]) queue.push({std::min(field.weight[g], field.weight[h.idx()]), -h.idx(), g});
    }
  }
  return flip;
}

// Connected parts of faces with the same flag smaller than `min_area` take the other flag
// (an umbilic's core, where the net turns within a few faces).
void MergeSmallParts(const SurfaceModel& surface, double min_area, std::vector<char>* flip) {
  const int n = surface.num_faces();
  std::vector<int> part(n, -1);
  std::vector<std::vector<int>> parts;
  for (int f = 0; f < n; ++f) {
    if (part[f] >= 0) continue;
    parts.push_back({f});
    part[f] = static_cast<int>(parts.size()) - 1;
    for (size_t k = 0; k < parts.back().size(); ++k)
      for (const auto h : surface.mesh().ff_range(FaceHandle(parts.back()[k])))
        if (part[h.idx()] < 0 && (*flip)[h.idx()] == (*flip)[f]) {
          part[h.idx()] = part[f];
          parts.back().push_back(h.idx());
        }
  }
  for (const auto& faces : parts) {
    double area = 0.0;
    for (const int f : faces) area += surface.face_area(f);
    if (area < min_area) for (const int f : faces) (*flip)[f] = !(*flip)[f];
  }
}

}  // namespace

int CombCurvatureNet(const SurfaceModel& surface, double min_area, GuidanceField* field) {
  std::vector<char> flip = CombingFlips(surface, *field);
  MergeSmallParts(surface, min_area, &flip);
  int swapped = 0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    if (!flip[f] || !(field->weight[f] > 0.0)) continue;  // no alignment there: left as it was
    field->direction[f] = surface.face_normal(f).cross(field->direction[f]);
    std::swap(field->major[f], field->minor[f]);
    ++swapped;
  }
  return swapped;
}

Status ComputeStrainGuidance(const SurfaceModel& surface, const std::vector<double>& v_z,
                             const GuidanceOptions& options, GuidanceField* field) {
  Resize(surface.num_faces(), field);
  // Each face on its own (base/parallel_ranges.h: the same bits on any number of threads).
  ParallelRanges(surface.num_faces(), [&](int begin, int end) {
    for (int f = begin; f < end; ++f) {
      const Eigen::Vector3d& n = surface.face_normal(f);
      const Eigen::Vector3d grad = FaceGradient(surface, f, v_z);
      const TangentEigen strain = DecomposeOnTangentPlane(GreenLagrangeStrain(n, grad), n);
      // Orientation (paper): ⟨e_max, P v⟩ > 0 with v the face's mean displacement. On a face
      // parallel to the ground P v vanishes; there the gradient of v_z decides instead.
      const auto ids = surface.face_vertices(f);
      const double mean_vz = (v_z[ids[0]] + v_z[ids[1]] + v_z[ids[2]]) / 3.0;
      const Eigen::Vector3d Pv = mean_vz * (Eigen::Vector3d::UnitZ() - n * n.z());
      const bool flat = Pv.norm() <= 1e-9 * std::abs(mean_vz);
      const double side = flat ? strain.major_direction.dot(grad) : strain.major_direction.dot(Pv);
      field->direction[f] = side < 0.0 ? -strain.major_direction : strain.major_direction;
      field->major[f] = strain.major;
      field->minor[f] = strain.minor;
      field->magnitude[f] = std::abs(strain.major);
    }
  });
  field->scale = *std::max_element(field->magnitude.begin(), field->magnitude.end());
  field->weight = AlignmentWeights(StrainDominance(*field, options), field->scale, options.threshold, options.ramp);
  return Status::Ok();
}

Status ComputeCurvatureGuidance(const SurfaceModel& surface, const GuidanceOptions& options, GuidanceField* field) {
  Resize(surface.num_faces(), field);
  const std::vector<Eigen::Matrix3d> shape = FaceShapeOperators(surface);
  // κ1 ≥ κ2 ordered by sign, oriented by the area-weighted mean curvature: on a synclastic
  // roof this is the direction of largest |κ| (as before), and where the mean curvature
  // changes sign (a hypar, a wavy roof) the field stays continuous instead of turning by 90°
  // along the lines κ1 = −κ2, which made spurious ±½ singularity pairs (70 on the hypar).
  double mean_curvature = 0.0;
  for (int f = 0; f < surface.num_faces(); ++f) mean_curvature += surface.face_area(f) * shape[f].trace();
  const int orientation = mean_curvature < 0.0 ? -1 : 1;
  std::vector<double> curvature_sum(surface.num_faces());
  ParallelRanges(surface.num_faces(), [&](int begin, int end) {
    for (int f = begin; f < end; ++f) {
      const TangentEigen curvature = DecomposeOnTangentPlane(shape[f], surface.face_normal(f), orientation);
      field->direction[f] = curvature.major_direction;
      field->major[f] = curvature.major;
      field->minor[f] = curvature.minor;
      field->magnitude[f] = std::abs(curvature.major - curvature.minor);
      curvature_sum[f] = std::abs(curvature.major) + std::abs(curvature.minor);
    }
  });
  // Scale: the 95th percentile of |κ1| + |κ2|, so that a few sharply curved faces (the Great
  // Court's rectangle corners) do not decide the weights of the whole roof.
  const auto rank = curvature_sum.begin() + static_cast<long>(0.95 * (curvature_sum.size() - 1));
  std::nth_element(curvature_sum.begin(), rank, curvature_sum.end());
  field->scale = *rank;
  field->weight = AlignmentWeights(field->magnitude, field->scale, options.threshold, options.ramp);
  return Status::Ok();
}

void AppendFace(const GuidanceField& from, int f, GuidanceField* to) {
  to->direction.push_back(from.direction[f]);
  to->major.push_back(from.major[f]);
  to->minor.push_back(from.minor[f]);
  to->magnitude.push_back(from.magnitude[f]);
  to->weight.push_back(from.weight[f]);
  if (from.source_weight.empty()) return;
  to->source_direction.push_back(from.source_direction[f]);
  to->source_weight.push_back(from.source_weight[f]);
}

double AddCurvatureFallback(const SurfaceModel& surface, const GuidanceField& curvature, double beta,
                            GuidanceField* field) {
  field->source_direction = field->direction;
  field->source_weight = field->weight;
  double area = 0.0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    const Eigen::Vector3d& n = surface.face_normal(f);
    const Eigen::Vector3d& d_k = curvature.direction[f];
    const double w_s = field->weight[f], w_c = (1.0 - w_s) * beta * curvature.weight[f];
    if (w_c > w_s) area += surface.face_area(f);
    Eigen::Vector3d e1 = field->direction[f] - field->direction[f].dot(n) * n;
    if (!(e1.norm() > 0.0) || !(w_s > 0.0)) {  // no source here: the curvature line alone
      field->direction[f] = d_k;
      field->weight[f] = std::min(1.0, w_c);
      continue;
    }
    e1.normalize();
    const Eigen::Vector3d e2 = n.cross(e1);
    const double theta = std::atan2(d_k.dot(e2), d_k.dot(e1));
    const double x = w_s + w_c * std::cos(2.0 * theta), y = w_c * std::sin(2.0 * theta);
    const double half = 0.5 * std::atan2(y, x);
    field->direction[f] = std::cos(half) * e1 + std::sin(half) * e2;
    field->weight[f] = std::min(1.0, std::hypot(x, y));
  }
  return area / surface.total_area();
}

namespace {

// One data line of a guidance file: its words and their values.
struct GuidanceRow {
  std::vector<std::string> words;
  std::vector<double> values;
  bool numeric = true;
};

GuidanceRow SplitRow(std::string line) {
  std::replace(line.begin(), line.end(), ',', ' ');
  std::istringstream words(line);
  GuidanceRow row;
  std::string word;
  while (words >> word) {
    char* end = nullptr;
    row.values.push_back(std::strtod(word.c_str(), &end));
    row.numeric = row.numeric && *end == '\0';
    row.words.push_back(word);
  }
  return row;
}

// The face a row is for. The id is range-checked as a double before the cast: NaN or 1e300
// cast to int is undefined behaviour.
Status RowFace(const GuidanceRow& row, int num_faces, int* face) {
  const double id = row.values[0];
  if (!(id >= 0.0 && id < num_faces && id == std::floor(id)))
    return Status::InvalidInput("face id '" + row.words[0] + "' is not a face of the surface (ids 0 to " +
                                std::to_string(num_faces - 1) + ")");
  *face = static_cast<int>(id);
  return Status::Ok();
}

// Larger direction components are refused: the field's magnitudes are drawn and compared
// (1e308 made the figure's colour bar overflow an int cast).
constexpr double kMaxComponent = 1e12;

// The row's direction projected onto face f's plane, scaled to its largest component first
// so that tiny vectors do not underflow; *magnitude is its length (0: no direction here).
Status RowDirection(const GuidanceRow& row, const Eigen::Vector3d& n, Eigen::Vector3d* unit, double* magnitude) {
  const Eigen::Vector3d d(row.values[1], row.values[2], row.values[3]);
  for (int k = 0; k < 3; ++k) {
    const std::string name = "d" + std::string(1, "xyz"[k]) + " is '" + row.words[1 + k] + "'";
    if (!std::isfinite(d[k])) return Status::InvalidInput(name + ", not a finite number");
    if (std::abs(d[k]) > kMaxComponent)
      return Status::InvalidInput(name + ", more than 1e12 in size (scale the field down)");
  }
  const double largest = d.cwiseAbs().maxCoeff();
  *magnitude = 0.0;
  if (largest == 0.0) return Status::Ok();
  const Eigen::Vector3d scaled = d / largest;
  const Eigen::Vector3d tangent = scaled - n * n.dot(scaled);
  if (tangent.norm() <= 1e-9) return Status::Ok();  // normal to the face: no direction in it
  *unit = tangent.normalized();
  *magnitude = largest * tangent.norm();
  return Status::Ok();
}

}  // namespace

Status ReadGuidanceFile(const SurfaceModel& surface, const GuidanceOptions& options, GuidanceField* field) {
  const std::string& path = options.file;
  if (path.empty()) return Status::InvalidInput("guidance.file: required when guidance.source is file");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return Status::InvalidInput(path + ": guidance file not found");
  if (!std::filesystem::is_regular_file(path, ec)) return Status::InvalidInput(path + ": not a guidance file (a folder?)");
  std::ifstream in(path);
  if (!in) return Status::InvalidInput(path + ": cannot read the guidance file");
  const int num_faces = surface.num_faces();
  Resize(num_faces, field);
  std::vector<double> given_weight(num_faces, 0.0);
  std::vector<int> line_of_face(num_faces, 0);
  size_t columns = 0;  // 4 or 5, fixed by the first data line
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const GuidanceRow row = SplitRow(line);
    if (row.values.empty() || (!row.numeric && line_number == 1)) continue;  // blank line or header
    const std::string where = path + ":" + std::to_string(line_number);
    if (!row.numeric || (row.values.size() != 4 && row.values.size() != 5))
      return Status::InvalidInput(where + ": expected id,dx,dy,dz[,weight]");
    if (columns == 0) columns = row.values.size();
    if (row.values.size() != columns)
      return Status::InvalidInput(where + ": " + std::to_string(row.values.size()) + " values, but the first line has " +
                                  std::to_string(columns) + " (give a weight on every line or on none)");
    int f = -1;
    PQ_RETURN_IF_ERROR(RowFace(row, num_faces, &f).WithContext(where));
    if (line_of_face[f] > 0)
      return Status::InvalidInput(where + ": face " + std::to_string(f) + " appears twice (first on line " +
                                  std::to_string(line_of_face[f]) + ")");
    line_of_face[f] = line_number;
    PQ_RETURN_IF_ERROR(RowDirection(row, surface.face_normal(f), &field->direction[f], &field->magnitude[f])
                           .WithContext(where + ": face " + std::to_string(f)));
    if (columns == 5) {
      const double w = row.values[4];
      if (!(w >= 0.0 && w <= 1.0))
        return Status::InvalidInput(where + ": weight must be in [0, 1], got '" + row.words[4] + "'");
      if (w > 0.0 && field->magnitude[f] == 0.0)
        return Status::InvalidInput(where + ": face " + std::to_string(f) + " has weight " + row.words[4] +
                                    " but no direction (zero, or normal to the face)");
      given_weight[f] = w;
    }
  }
  const auto missing = std::find(line_of_face.begin(), line_of_face.end(), 0);
  if (missing != line_of_face.end())
    return Status::InvalidInput(path + ": no direction for face " + std::to_string(missing - line_of_face.begin()) +
                                " (the surface has " + std::to_string(num_faces) + " faces)");
  field->scale = *std::max_element(field->magnitude.begin(), field->magnitude.end());
  if (!(field->scale > 0.0))
    return Status::InvalidInput(path + ":" + std::to_string(line_of_face[0]) +
                                ": every direction is zero or normal to the surface (this line is face 0's): "
                                "there is no guidance to follow");
  for (int f = 0; f < num_faces; ++f) {
    // Faces without a direction get a unit one in their plane (the field's invariant) and no
    // weight, so that no solver ever normalises a zero vector.
    if (field->magnitude[f] > 0.0) continue;
    const auto ids = surface.face_vertices(f);
    field->direction[f] = (surface.position(ids[1]) - surface.position(ids[0])).normalized();
  }
  field->weight = columns == 5 ? given_weight
                                : AlignmentWeights(field->magnitude, field->scale, options.threshold, options.ramp);
  for (int f = 0; f < num_faces; ++f)
    if (field->magnitude[f] == 0.0) field->weight[f] = 0.0;
  return Status::Ok();
}

}  // namespace pqlayout
