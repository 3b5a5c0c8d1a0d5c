#include "geometry/streamlines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>
#include <utility>

#include <Eigen/Geometry>

#include "geometry/line_field_singularities.h"

namespace pqlayout {
namespace {

using Eigen::Vector2d;

// A projected triangle counts as degenerate below this ratio of projected to true area.
constexpr double kMinProjectedAreaRatio = 1e-6;
// Barycentric tolerance of the point-in-triangle test (points on edges are inside).
constexpr double kInsideTolerance = 1e-10;
// Samples of the growing line closer along it than this × dsep never stop it.
constexpr double kSelfGapRatio = 2.0;
// Bisection steps that clip a line onto the boundary.
constexpr int kClipIterations = 30;

double Cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The projected triangles that carry a field, with a uniform grid for point location.
class TopViewLocator {
 public:
  // Faces with `blocked` set carry no field.
  TopViewLocator(const SurfaceModel& surface, const std::vector<Eigen::Vector3d>& directions,
                 const std::vector<char>& blocked, double min_projected_norm) {
    const int nf = surface.num_faces();
    triangles_.resize(nf);
    direction_.assign(nf, Vector2d::Zero());
    std::vector<int> valid;
    for (int f = 0; f < nf; ++f) {
      const auto ids = surface.face_vertices(f);
      for (int k = 0; k < 3; ++k) triangles_[f][k] = surface.position(ids[k]).head<2>();
      const Eigen::Vector3d& d = directions[f];
      const double projected_area = 0.5 * std::abs(Cross(triangles_[f][1] - triangles_[f][0],
                                                         triangles_[f][2] - triangles_[f][0]));
      if (blocked[f] || !d.allFinite() || d.head<2>().norm() <= min_projected_norm * d.norm() ||
          !(projected_area > kMinProjectedAreaRatio * surface.face_area(f)))
        continue;
      direction_[f] = d.head<2>().normalized();
      for (const auto& p : triangles_[f]) bounds_.extend(p);
      valid.push_back(f);
    }
    if (!valid.empty()) BuildGrid(valid);
  }

  bool empty() const { return cell_start_.empty(); }
  const Eigen::AlignedBox2d& bounds() const { return bounds_; }
  const Vector2d& direction(int f) const { return direction_[f]; }

  // The face with a field containing p (trying `hint` first), or -1.
  int Locate(const Vector2d& p, int hint = -1) const {
    if (empty()) return -1;
    if (hint >= 0 && Contains(hint, p)) return hint;
    const int c = Cell(p);
    if (c < 0) return -1;
    for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
      if (Contains(cell_faces_[k], p)) return cell_faces_[k];
    return -1;
  }

 private:
  void BuildGrid(const std::vector<int>& faces) {
    const Vector2d size = bounds_.sizes().cwiseMax(1e-12);
    cell_ = std::sqrt(size.x() * size.y() / faces.size());
    cell_ = std::max({cell_, size.x() / 4096.0, size.y() / 4096.0});
    nx_ = std::max(1, static_cast<int>(std::ceil(size.x() / cell_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(size.y() / cell_)));
    std::vector<int> count(nx_ * ny_ + 1, 0);
    ForEachCell(faces, [&](int, int c) { ++count[c + 1]; });
    for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    cell_start_ = count;
    cell_faces_.resize(count.back());
    ForEachCell(faces, [&](int f, int c) { cell_faces_[count[c]++] = f; });
  }

  template <typename Visit>
  void ForEachCell(const std::vector<int>& faces, const Visit& visit) const {
    for (const int f : faces) {
      Eigen::AlignedBox2d box;
      for (const auto& p : triangles_[f]) box.extend(p);
      const auto [i0, j0] = CellIndex(box.min());
      const auto [i1, j1] = CellIndex(box.max());
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) visit(f, j * nx_ + i);
    }
  }

  std::pair<int, int> CellIndex(const Vector2d& p) const {
    const Vector2d q = (p - bounds_.min()) / cell_;
    return {std::clamp(static_cast<int>(std::floor(q.x())), 0, nx_ - 1),
            std::clamp(static_cast<int>(std::floor(q.y())), 0, ny_ - 1)};
  }

  int Cell(const Vector2d& p) const {
    if (!bounds_.contains(p)) return -1;
    const auto [i, j] = CellIndex(p);
    return j * nx_ + i;
  }

  bool Contains(int f, const Vector2d& p) const {
    const auto& t = triangles_[f];
    const double area = Cross(t[1] - t[0], t[2] - t[0]);
    const double l0 = Cross(t[1] - p, t[2] - p) / area;
    const double l1 = Cross(t[2] - p, t[0] - p) / area;
    return l0 >= -kInsideTolerance && l1 >= -kInsideTolerance && 1.0 - l0 - l1 >= -kInsideTolerance;
  }

  std::vector<std::array<Vector2d, 3>> triangles_;
  std::vector<Vector2d> direction_;  // unit xy direction; zero where there is no field
  Eigen::AlignedBox2d bounds_;       // of the faces with a field
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_, cell_faces_;  // faces of cell c: [start[c], start[c+1])
};

// Line samples binned in a grid of cell size >= the largest query radius.
class SampleGrid {
 public:
  struct Sample {
    Vector2d p;
    int line;    // index of the line
    double arc;  // signed arc length from the line's seed
  };

  SampleGrid(const Eigen::AlignedBox2d& bounds, double radius) : origin_(bounds.min()) {
    const Vector2d size = bounds.sizes().cwiseMax(1e-12);
    cell_ = std::max({radius, size.x() / 2048.0, size.y() / 2048.0});
    nx_ = static_cast<int>(std::ceil(size.x() / cell_)) + 1;
    ny_ = static_cast<int>(std::ceil(size.y() / cell_)) + 1;
    cells_.resize(static_cast<size_t>(nx_) * ny_);
  }

  void Add(const Sample& sample) {
    const int c = CellOf(sample.p);
    cells_[c].push_back(sample);
    added_.push_back(c);
  }

  // Removes the samples of the newest line (they were added last).
  void RemoveLine(int line) {
    while (!added_.empty() && cells_[added_.back()].back().line == line) {
      cells_[added_.back()].pop_back();
      added_.pop_back();
    }
  }

  // True if a sample lies closer than r to p, ignoring samples of line `self` whose arc
  // length differs from `arc` by less than self_gap.
  bool Near(const Vector2d& p, double r, int self, double arc, double self_gap) const {
    const int ci = Clamp((p.x() - origin_.x()) / cell_, nx_),
              cj = Clamp((p.y() - origin_.y()) / cell_, ny_);
    for (int j = std::max(cj - 1, 0); j <= std::min(cj + 1, ny_ - 1); ++j)
      for (int i = std::max(ci - 1, 0); i <= std::min(ci + 1, nx_ - 1); ++i)
        for (const Sample& s : cells_[j * nx_ + i]) {
          if (s.line == self && std::abs(s.arc - arc) < self_gap) continue;
          if ((s.p - p).squaredNorm() < r * r) return true;
        }
    return false;
  }

 private:
  static int Clamp(double x, int n) {
    return std::clamp(static_cast<int>(std::floor(x)), 0, n - 1);
  }
  int CellOf(const Vector2d& p) const {
    return Clamp((p.y() - origin_.y()) / cell_, ny_) * nx_ +
           Clamp((p.x() - origin_.x()) / cell_, nx_);
  }

  Vector2d origin_;
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<Sample>> cells_;
  std::vector<int> added_;  // cell of every sample, in order of addition
};

class EvenlySpacedTracer {
 public:
  EvenlySpacedTracer(const TopViewLocator& field, const StreamlineOptions& options)
      : field_(field),
        dsep_(options.separation),
        dtest_(options.test_ratio * options.separation),
        step_(options.step_ratio * options.separation),
        min_length_(options.min_length_ratio * options.separation),
        max_length_(options.max_length_ratio * field.bounds().diagonal().norm()),
        cos_max_turn_(std::cos(options.max_turn_deg * M_PI / 180.0)),
        samples_(field.bounds(), options.separation) {}

  std::vector<std::vector<Vector2d>> Run() {
    const Eigen::AlignedBox2d& box = field_.bounds();
    for (double y = box.min().y() + 0.5 * dsep_; y <= box.max().y(); y += dsep_)
      for (double x = box.min().x() + 0.5 * dsep_; x <= box.max().x(); x += dsep_) {
        TryLine({x, y});
        SeedAlongNewLines();
      }
    return std::move(lines_);
  }

 private:
  // Traces from `seed` if it is a valid seed; keeps the line if it is long enough.
  void TryLine(const Vector2d& seed) {
    const int face = field_.Locate(seed);
    if (face < 0 || samples_.Near(seed, dsep_ * (1.0 - 1e-9), -1, 0.0, 0.0)) return;
    Vector2d d = field_.direction(face);
    if (d.x() < 0.0 || (d.x() == 0.0 && d.y() < 0.0)) d = -d;  // sign-independent start
    const int id = static_cast<int>(lines_.size());
    samples_.Add({seed, id, 0.0});
    std::vector<Vector2d> forward = Grow(seed, d, +1.0, id);
    std::vector<Vector2d> backward = Grow(seed, -d, -1.0, id);
    if (Length(forward) + Length(backward) < min_length_) {
      samples_.RemoveLine(id);
      return;
    }
    std::reverse(backward.begin(), backward.end());
    backward.pop_back();  // the seed, also first in `forward`
    backward.insert(backward.end(), forward.begin(), forward.end());
    lines_.push_back(std::move(backward));
    queue_.push_back(id);
  }

  // Seeds at distance dsep on both sides of every accepted line, breadth-first.
  void SeedAlongNewLines() {
    while (!queue_.empty()) {
      const int id = queue_.front();
      queue_.pop_front();
      const std::vector<Vector2d> line = lines_[id];  // a copy: TryLine appends to lines_
      for (size_t i = 0; i < line.size(); ++i) {
        const Vector2d tangent =
            (line[std::min(i + 1, line.size() - 1)] - line[i > 0 ? i - 1 : 0]).normalized();
        const Vector2d normal(-tangent.y(), tangent.x());
        for (const double side : {1.0, -1.0}) TryLine(line[i] + side * dsep_ * normal);
      }
    }
  }

  // The field at p aligned with `previous`, or nothing outside the field.
  std::optional<Vector2d> FieldAt(const Vector2d& p, const Vector2d& previous, int* face) const {
    *face = field_.Locate(p, *face);
    if (*face < 0) return std::nullopt;
    const Vector2d& d = field_.direction(*face);
    return d.dot(previous) < 0.0 ? Vector2d(-d) : d;
  }

  // Grows one side of line `id` from `seed` along `d`; arc lengths get sign `sense`.
  std::vector<Vector2d> Grow(const Vector2d& seed, const Vector2d& d, double sense, int id) {
    std::vector<Vector2d> points{seed};
    std::vector<Vector2d> headings{d};  // of every step, to bound the turning over dsep
    const size_t window = std::max<long>(1, std::lround(dsep_ / step_));
    int face = -1;
    for (double arc = 0.0; arc < max_length_; arc += step_) {
      const Vector2d p = points.back();
      const auto k1 = FieldAt(p, headings.back(), &face);
      if (!k1) break;
      int mid_face = face;
      const auto k2 = FieldAt(p + 0.5 * step_ * *k1, *k1, &mid_face);
      const Vector2d heading = k2 ? *k2 : *k1;
      if (heading.dot(headings[headings.size() - std::min(window, headings.size())]) <
          cos_max_turn_)
        break;  // turning too fast: a singularity
      const Vector2d q = p + step_ * heading;
      if (!k2 || field_.Locate(q, mid_face) < 0) {
        AddIfFree(ClipToField(p, q), sense * (arc + step_), id, &points);
        break;
      }
      if (!AddIfFree(q, sense * (arc + step_), id, &points)) break;
      headings.push_back(heading);
    }
    return points;
  }

  // Appends q (and records it) unless it is closer than dtest to a line; returns whether.
  bool AddIfFree(const Vector2d& q, double arc, int id, std::vector<Vector2d>* points) {
    if ((q - points->back()).norm() < 1e-9 * step_) return false;
    if (samples_.Near(q, dtest_, id, arc, kSelfGapRatio * dsep_)) return false;
    samples_.Add({q, id, arc});
    points->push_back(q);
    return true;
  }

  // The last point of segment inside -> outside that lies in the field (bisection).
  Vector2d ClipToField(const Vector2d& inside, const Vector2d& outside) const {
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < kClipIterations; ++k) {
      const double mid = 0.5 * (lo + hi);
      (field_.Locate(inside + mid * (outside - inside)) >= 0 ? lo : hi) = mid;
    }
    return inside + lo * (outside - inside);
  }

  static double Length(const std::vector<Vector2d>& points) {
    double length = 0.0;
    for (size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
    return length;
  }

  const TopViewLocator& field_;
  const double dsep_, dtest_, step_, min_length_, max_length_, cos_max_turn_;
  SampleGrid samples_;
  std::vector<std::vector<Vector2d>> lines_;
  std::deque<int> queue_;  // accepted lines whose sides are not yet seeded
};

// Marks the faces around the vertices where the line field has a non-zero index.
std::vector<char> FacesAtSingularities(const SurfaceModel& surface,
                                       const std::vector<Eigen::Vector3d>& directions,
                                       const StreamlineOptions& options) {
  std::vector<char> blocked(surface.num_faces(), 0);
  if (!options.stop_at_singularities) return blocked;
  std::vector<LineFieldSingularity> found;
  if (options.singularities == nullptr) found = FindLineFieldSingularities(surface, directions);
  for (const auto& singularity : options.singularities != nullptr ? *options.singularities : found)
    for (const auto f : surface.mesh().vf_range(VertexHandle(singularity.vertex)))
      blocked[f.idx()] = 1;
  return blocked;
}

}  // namespace

std::vector<std::vector<Eigen::Vector2d>> EvenlySpacedStreamlines(
    const SurfaceModel& surface, const std::vector<Eigen::Vector3d>& directions,
    const StreamlineOptions& options) {
  if (!(options.separation > 0.0) || !(options.step_ratio > 0.0) ||
      static_cast<int>(directions.size()) != surface.num_faces())
    return {};
  const TopViewLocator field(surface, directions,
                             FacesAtSingularities(surface, directions, options),
                             options.min_projected_norm);
  if (field.empty()) return {};
  return EvenlySpacedTracer(field, options).Run();
}

}  // namespace pqlayout
