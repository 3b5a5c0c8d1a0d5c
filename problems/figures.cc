#include "problems/figures.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/level_lines.h"
#include "geometry/planarity.h"
#include "geometry/streamlines.h"
#include "geometry/svg_canvas.h"

namespace pqlayout {
namespace {

using Eigen::Vector2d;
using Rings = std::vector<std::vector<Vector2d>>;

constexpr int kColourLevels = 64;           // colour quantisation of the resampled grid
constexpr double kNotEnforcedWeight = 0.5;  // weight below this: alignment not enforced
constexpr double kSignedTolerance = 1e-3;   // a sign counts above this × the other's size
const Rgb kMutedBrown{0xc4, 0xa2, 0x7a};    // hatch of the not-enforced region
const Rgb kOutline{0, 0, 0};                // boundary outline
const Stroke kStreamline{Rgb{0x30, 0x30, 0x30}, 1.1, 0.9};  // integral curves
const Stroke kFaintStreamline{Rgb{0xb0, 0xb0, 0xb0}, 0.9, 0.9};  // background curves
const Stroke kPhiLine{Rgb{0x00, 0x00, 0x00}, 1.5, 1.0};           // φ = i·h (paper: black)
const Stroke kPsiLine{Rgb{0x1f, 0x5f, 0xd6}, 1.5, 1.0};           // ψ = j·h (paper: blue)
const Stroke kSeamLine{Rgb{0xd6, 0x27, 0x28}, 1.2, 0.8};          // seams of a branched layout
constexpr double kMinLevelSpacingPx = 4.0;  // closer level lines (px of 1000 px): every k-th
constexpr double kMaxLevelLines = 1000.0;   // per family, whatever the function's range

// The colour map and value range for a field: a symmetric diverging map for values of
// both signs, viridis from min to max otherwise.
struct ColourScale {
  ColourMap map = Viridis;
  double lo = 0.0, hi = 1.0;
  double T(double value) const { return hi > lo ? (value - lo) / (hi - lo) : 0.5; }
};

ColourScale ScaleFor(const std::vector<double>& values, bool allow_diverging) {
  const auto [min_it, max_it] = std::minmax_element(values.begin(), values.end());
  ColourScale scale{Viridis, *min_it, *max_it};
  const double extent = std::max(-scale.lo, scale.hi);
  if (allow_diverging && -scale.lo > kSignedTolerance * extent &&
      scale.hi > kSignedTolerance * extent)
    scale = {BlueWhiteRed, -extent, extent};
  if (!(scale.hi > scale.lo)) {  // constant field: ±50 % around it (±1 around zero)
    const double pad = scale.lo == 0.0 ? 1.0 : 0.5 * std::abs(scale.lo);
    scale.lo -= pad;
    scale.hi += pad;
  }
  return scale;
}

Vector2d Xy(const SurfaceModel& surface, int v) { return surface.position(v).head<2>(); }

Eigen::AlignedBox2d TopViewBounds(const SurfaceModel& surface) {
  return Eigen::AlignedBox2d(surface.bbox_min().head<2>(), surface.bbox_max().head<2>());
}

// Fills every face with its own polygon.
void DrawFacePolygons(const SurfaceModel& surface, const std::vector<double>& face_values,
                      const ColourScale& scale, SvgCanvas* canvas) {
  std::vector<Vector2d> triangle(3);
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    for (int k = 0; k < 3; ++k) triangle[k] = Xy(surface, ids[k]);
    canvas->Polygon(triangle, scale.map(scale.T(face_values[f])));
  }
}

// Indices i whose cell centre (i + ½)·cell lies in [lo, hi] (both in cells), within [0, n).
std::pair<int, int> CentresWithin(double lo, double hi, int n) {
  return {std::max(0, static_cast<int>(std::ceil(lo - 0.5))),
          std::min(n - 1, static_cast<int>(std::floor(hi - 0.5)))};
}

double Cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// A field to colour: one value per face, or one per vertex interpolated linearly inside
// each triangle (vertex_values non-empty).
struct FieldValues {
  const std::vector<double>& face_values;
  const std::vector<double>& vertex_values;
};

// Colour level (0..kColourLevels-1) of every grid cell whose centre lies in a face, -1
// elsewhere; cells of size `cell` metres cover `box` row by row from its min corner.
std::vector<int> RasteriseLevels(const SurfaceModel& surface, const FieldValues& field,
                                 const ColourScale& scale, const Eigen::AlignedBox2d& box,
                                 double cell, int nx, int ny) {
  constexpr double kTolerance = 1e-9;  // centres on a shared edge belong to both faces
  const bool smooth = !field.vertex_values.empty();
  const auto level_of = [&](double value) {
    return std::clamp(static_cast<int>(scale.T(value) * kColourLevels), 0, kColourLevels - 1);
  };
  std::vector<int> level(static_cast<size_t>(nx) * ny, -1);
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    const Vector2d a = Xy(surface, ids[0]), b = Xy(surface, ids[1]), c = Xy(surface, ids[2]);
    const double area = Cross(b - a, c - a);
    if (area == 0.0) continue;
    const Vector2d lo = (a.cwiseMin(b).cwiseMin(c) - box.min()) / cell;
    const Vector2d hi = (a.cwiseMax(b).cwiseMax(c) - box.min()) / cell;
    const auto [i0, i1] = CentresWithin(lo.x(), hi.x(), nx);
    const auto [j0, j1] = CentresWithin(lo.y(), hi.y(), ny);
    const int flat = smooth ? 0 : level_of(field.face_values[f]);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vector2d p = box.min() + cell * Vector2d(i + 0.5, j + 0.5);
        const double l0 = Cross(b - p, c - p) / area, l1 = Cross(c - p, a - p) / area;
        if (l0 >= -kTolerance && l1 >= -kTolerance && l0 + l1 <= 1.0 + kTolerance)
          level[static_cast<size_t>(j) * nx + i] =
              smooth ? level_of(l0 * field.vertex_values[ids[0]] + l1 * field.vertex_values[ids[1]] +
                                (1.0 - l0 - l1) * field.vertex_values[ids[2]])
                     : flat;
      }
  }
  return level;
}

// Resamples the field onto a grid of small squares and merges runs of equal colour along
// each row into one box; one <path> per colour level.
void DrawResampledColours(const SurfaceModel& surface, const FieldValues& field,
                          const ColourScale& scale, const FigureOptions& options,
                          SvgCanvas* canvas) {
  const Eigen::AlignedBox2d box = TopViewBounds(surface);
  const double cell = options.grid_cell_px * canvas->unit() / canvas->px_per_metre();
  const int nx = std::max(1, static_cast<int>(std::ceil(box.sizes().x() / cell)));
  const int ny = std::max(1, static_cast<int>(std::ceil(box.sizes().y() / cell)));
  const std::vector<int> level = RasteriseLevels(surface, field, scale, box, cell, nx, ny);
  std::vector<std::vector<Eigen::AlignedBox2d>> boxes(kColourLevels);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx;) {
      const int t = level[static_cast<size_t>(j) * nx + i];
      int end = i + 1;
      while (end < nx && level[static_cast<size_t>(j) * nx + end] == t) ++end;
      if (t >= 0)
        boxes[t].emplace_back(box.min() + cell * Vector2d(i, j),
                              box.min() + cell * Vector2d(end, j + 1));
      i = end;
    }
  for (int t = 0; t < kColourLevels; ++t)
    canvas->Boxes(boxes[t], scale.map((t + 0.5) / kColourLevels));
}

void DrawFaceColours(const SurfaceModel& surface, const std::vector<double>& face_values,
                     const ColourScale& scale, const FigureOptions& options, SvgCanvas* canvas) {
  if (surface.num_faces() <= options.max_face_polygons)
    DrawFacePolygons(surface, face_values, scale, canvas);
  else
    DrawResampledColours(surface, {face_values, {}}, scale, options, canvas);
}

// The outline of a set of faces as closed rings (outer rings and holes), walking the
// halfedges that have a face of the set on their left and none on their right.
Rings RegionOutline(const SurfaceModel& surface, const std::vector<char>& in_region) {
  const TriMesh& mesh = surface.mesh();
  const auto inside = [&](HalfedgeHandle h) {
    const FaceHandle f = mesh.face_handle(h);
    return f.is_valid() && in_region[f.idx()];
  };
  const auto next_on_outline = [&](HalfedgeHandle h) {
    HalfedgeHandle n = mesh.next_halfedge_handle(h);
    while (inside(mesh.opposite_halfedge_handle(n)))
      n = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(n));
    return n;
  };
  std::vector<char> used(mesh.n_halfedges(), 0);
  Rings rings;
  for (const auto start : mesh.halfedges()) {
    if (used[start.idx()] || !inside(start) || inside(mesh.opposite_halfedge_handle(start)))
      continue;
    std::vector<Vector2d> ring;
    for (HalfedgeHandle h = start; !used[h.idx()]; h = next_on_outline(h)) {
      used[h.idx()] = 1;
      ring.push_back(Xy(surface, mesh.from_vertex_handle(h).idx()));
    }
    rings.push_back(std::move(ring));
  }
  return rings;
}

Rings BoundaryOutline(const SurfaceModel& surface) {
  Rings rings;
  for (const auto& loop : surface.boundary_loops()) {
    std::vector<Vector2d> ring;
    for (const auto v : loop.vertices) ring.push_back(Xy(surface, v.idx()));
    rings.push_back(std::move(ring));
  }
  return rings;
}

// Boundary outline, scale bar and north arrow.
void DrawOutlineScaleAndNorth(const SurfaceModel& surface, SvgCanvas* canvas) {
  canvas->Polylines(BoundaryOutline(surface), Stroke{kOutline, SvgStyle::kOutlineWidth, 1.0}, true);
  canvas->ScaleBar();
  canvas->NorthArrow();
}

void DrawFrame(const SurfaceModel& surface, const ColourScale& scale, const std::string& label,
               SvgCanvas* canvas) {
  DrawOutlineScaleAndNorth(surface, canvas);
  canvas->ColourBar(scale.map, scale.lo, scale.hi, label);
}

// The faces with weight < 0.5 as one hatched region; returns the hatch fill for the legend.
std::string DrawNotEnforcedRegion(const SurfaceModel& surface, const std::vector<double>& weight,
                                  SvgCanvas* canvas) {
  std::vector<char> not_enforced(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) not_enforced[f] = weight[f] < kNotEnforcedWeight;
  const std::string hatch = canvas->HatchFill(kMutedBrown);
  canvas->Region(RegionOutline(surface, not_enforced), hatch);
  return hatch;
}

std::vector<std::vector<Vector2d>> GuidanceCurves(const SurfaceModel& surface,
                                                  const std::vector<Eigen::Vector3d>& direction,
                                                  const FigureOptions& options,
                                                  const SvgCanvas& canvas) {
  StreamlineOptions streamlines;
  streamlines.separation = options.streamline_spacing_px * canvas.unit() / canvas.px_per_metre();
  return EvenlySpacedStreamlines(surface, direction, streamlines);
}

// The integer levels first, first + stride, ... ≤ last drawn for one function: every one
// unless they would be closer than kMinLevelSpacingPx (min_stride) or more than
// kMaxLevelLines.
struct LevelSelection {
  double first = 0.0;
  double stride = 1.0;
  int count = 0;
};

LevelSelection SelectLevels(const std::vector<double>& values, double min_stride) {
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const double range = std::floor(*hi) - std::ceil(*lo) + 1.0;
  LevelSelection levels;
  levels.stride = std::max(min_stride, std::ceil(range / kMaxLevelLines));
  levels.first = std::ceil(*lo / levels.stride) * levels.stride;
  levels.count = *hi < levels.first
                     ? 0
                     : static_cast<int>(std::floor((*hi - levels.first) / levels.stride)) + 1;
  return levels;
}

// The level lines of the selected levels in the top view.
Rings TopViewLevelLines(const SurfaceModel& surface, const std::vector<double>& values,
                        const LevelSelection& levels) {
  Rings lines;
  for (int k = 0; k < levels.count; ++k)
    for (const auto& line : LevelLines(surface, values, levels.first + k * levels.stride)) {
      std::vector<Vector2d> xy;
      xy.reserve(line.size());
      for (const auto& p : line) xy.push_back(p.head<2>());
      lines.push_back(std::move(xy));
    }
  return lines;
}

std::string LevelLegendLabel(const std::string& family, double spacing, double stride,
                             const std::string& meaning) {
  std::ostringstream label;
  label.precision(3);
  label << "level lines " << family << ", h = " << spacing << " m";
  if (stride > 1.0) label << ", one in " << stride << " drawn";
  label << " (" << meaning << ")";
  return label.str();
}

Status CheckFinite(const std::vector<double>& values, int expected, const std::string& name,
                   const std::string& element) {
  if (static_cast<int>(values.size()) != expected)
    return Status::InvalidInput(name + " has " + std::to_string(values.size()) +
                                " values, expected " + std::to_string(expected) + " (one per " +
                                element + ")");
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      return Status::InvalidInput(name + " is not finite at " + element + " " + std::to_string(i));
  return Status::Ok();
}

}  // namespace

Status WriteDisplacementFigure(const SurfaceModel& surface, const std::vector<double>& v_z,
                               const std::string& title, const std::string& path,
                               const FigureOptions& options) {
  PQ_RETURN_IF_ERROR(CheckFinite(v_z, surface.num_vertices(), "v_z", "vertex").WithContext(path));
  std::vector<double> vertex_mm(v_z.size());
  std::transform(v_z.begin(), v_z.end(), vertex_mm.begin(), [](double v) { return 1000.0 * v; });
  const ColourScale scale = ScaleFor(vertex_mm, /*allow_diverging=*/true);
  SvgCanvas canvas(TopViewBounds(surface), options.width_px, title);
  // A vertex field: always resampled with linear interpolation inside each triangle, so the
  // map is smooth (64 colour bands, like contours) whatever the face count.
  DrawResampledColours(surface, {{}, vertex_mm}, scale, options, &canvas);
  DrawFrame(surface, scale, "v_z [mm]", &canvas);
  return canvas.Write(path);
}

Status WriteGuidanceFigure(const SurfaceModel& surface,
                           const std::vector<Eigen::Vector3d>& direction,
                           const std::vector<double>& magnitude, const std::string& magnitude_label,
                           const std::vector<double>& weight, const std::string& title,
                           const std::string& path, const FigureOptions& options) {
  const int nf = surface.num_faces();
  if (static_cast<int>(direction.size()) != nf)
    return Status::InvalidInput(path + ": direction has " + std::to_string(direction.size()) +
                                " vectors, expected " + std::to_string(nf) + " (one per face)");
  PQ_RETURN_IF_ERROR(CheckFinite(magnitude, nf, magnitude_label, "face").WithContext(path));
  PQ_RETURN_IF_ERROR(CheckFinite(weight, nf, "weight", "face").WithContext(path));
  const ColourScale scale = ScaleFor(magnitude, /*allow_diverging=*/false);
  SvgCanvas canvas(TopViewBounds(surface), options.width_px, title);
  DrawFaceColours(surface, magnitude, scale, options, &canvas);

  const std::string hatch = DrawNotEnforcedRegion(surface, weight, &canvas);
  canvas.HaloPolylines(GuidanceCurves(surface, direction, options, canvas), kStreamline);

  DrawFrame(surface, scale, magnitude_label, &canvas);
  canvas.Legend({{hatch, "alignment not enforced (weight < 0.5)"}});
  return canvas.Write(path);
}

Status WriteLevelSetFigure(const SurfaceModel& surface, const std::vector<double>& phi,
                           const std::vector<double>& psi, double spacing,
                           const std::vector<Eigen::Vector3d>& direction,
                           const std::vector<double>& weight, const std::string& title,
                           const std::string& path, const FigureOptions& options, const SeamCut* seams) {
  const int nf = surface.num_faces();
  const SurfaceModel& level_surface = seams != nullptr ? seams->cut() : surface;
  PQ_RETURN_IF_ERROR(CheckFinite(phi, level_surface.num_vertices(), "phi", "vertex").WithContext(path));
  PQ_RETURN_IF_ERROR(CheckFinite(psi, level_surface.num_vertices(), "psi", "vertex").WithContext(path));
  if (static_cast<int>(direction.size()) != nf)
    return Status::InvalidInput(path + ": direction has " + std::to_string(direction.size()) +
                                " vectors, expected " + std::to_string(nf) + " (one per face)");
  PQ_RETURN_IF_ERROR(CheckFinite(weight, nf, "weight", "face").WithContext(path));
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    return Status::InvalidInput(path + ": spacing h must be a positive number, got " +
                                std::to_string(spacing));
  SvgCanvas canvas(TopViewBounds(surface), options.width_px, title);
  const std::string hatch = DrawNotEnforcedRegion(surface, weight, &canvas);
  canvas.Polylines(GuidanceCurves(surface, direction, options, canvas), kFaintStreamline);

  // Lines h apart in the world are h · px_per_metre apart in the drawing.
  const double spacing_px = spacing * canvas.px_per_metre() / canvas.unit();
  const double min_stride = std::max(1.0, std::ceil(kMinLevelSpacingPx / spacing_px));
  const LevelSelection phi_levels = SelectLevels(phi, min_stride);
  const LevelSelection psi_levels = SelectLevels(psi, min_stride);
  canvas.Polylines(TopViewLevelLines(level_surface, psi, psi_levels), kPsiLine);
  canvas.Polylines(TopViewLevelLines(level_surface, phi, phi_levels), kPhiLine);
  std::vector<LegendEntry> legend{
      {kPhiLine.colour.Hex(), LevelLegendLabel("φ = i·h", spacing, phi_levels.stride, "aligned with the guidance")},
      {kPsiLine.colour.Hex(), LevelLegendLabel("ψ = j·h", spacing, psi_levels.stride, "conjugate to φ")},
      {kFaintStreamline.colour.Hex(), "integral curves of the guidance field"},
      {hatch, "alignment not enforced (weight < 0.5)"}};
  if (seams != nullptr && seams->num_paths() > 0) {
    Rings paths;
    for (int p = 0; p < seams->num_paths(); ++p) {
      std::vector<Vector2d> xy;
      for (const int v : seams->path(p)) xy.push_back(seams->position(v).head<2>());
      paths.push_back(std::move(xy));
      if (seams->starts_inside(p)) canvas.Circle(paths.back().front(), 4.0, kSeamLine.colour);
    }
    canvas.Polylines(paths, kSeamLine);
    legend.push_back({kSeamLine.colour.Hex(), "seams (level lines continue across; dots: branch points)"});
  }

  DrawOutlineScaleAndNorth(surface, &canvas);
  canvas.Legend(legend);
  return canvas.Write(path);
}

namespace {
constexpr double kMinEdgePx = 4.0;    // shorter edges on the drawing: no member lines
constexpr double kOpaqueEdgePx = 15.0;  // from here on, lines at full opacity
}  // namespace

double MeshLineWidth(double mean_edge_px) {
  constexpr double kRatio = 0.05, kMinWidth = 0.3, kMaxWidth = 1.2;
  if (!(mean_edge_px >= kMinEdgePx)) return 0.0;
  return std::clamp(kRatio * mean_edge_px, kMinWidth, kMaxWidth);
}

double MeshLineOpacity(double mean_edge_px) {
  constexpr double kMinOpacity = 0.35, kMaxOpacity = 0.9;
  const double s = std::clamp((mean_edge_px - kMinEdgePx) / (kOpaqueEdgePx - kMinEdgePx), 0.0, 1.0);
  return kMinOpacity + s * (kMaxOpacity - kMinOpacity);
}

double PlanarityScale::lo() const { return target * std::pow(10.0, -kDecades); }
double PlanarityScale::hi() const { return target * std::pow(10.0, kDecades); }
Rgb PlanarityScale::Colour(double delta) const {
  if (!(delta > lo())) return BlueWhiteRed(0.0);
  return BlueWhiteRed((std::log10(delta / target) + kDecades) / (2.0 * kDecades));
}

namespace {

const Rgb kMemberInk{0x28, 0x28, 0x28};  // grid-shell members
const Rgb kFaintFace{0xe6, 0xe6, 0xe6};  // faces behind coloured members

std::vector<Eigen::Vector3d> FacePoints(const PolyMesh& mesh, FaceHandle f) {
  std::vector<Eigen::Vector3d> points;
  for (const auto v : mesh.fv_range(f)) points.push_back(ToEigen(mesh.point(v)));
  return points;
}

std::vector<Vector2d> TopView(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Vector2d> xy;
  for (const auto& p : points) xy.push_back(p.head<2>());
  return xy;
}

double MeanEdgeLength(const PolyMesh& mesh) {
  double sum = 0.0;
  for (const auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return mesh.n_edges() > 0 ? sum / mesh.n_edges() : 0.0;
}

// The member stroke for this mesh on this canvas; width 0 if the members would be too dense.
Stroke MemberStroke(const PolyMesh& mesh, const SvgCanvas& canvas) {
  const double edge_px = MeanEdgeLength(mesh) * canvas.px_per_metre() / canvas.unit();
  return Stroke{kMemberInk, MeshLineWidth(edge_px), MeshLineOpacity(edge_px)};
}

// Every edge of the mesh as a segment in the top view.
Rings TopViewEdges(const PolyMesh& mesh) {
  Rings members;
  for (const auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    members.push_back({ToEigen(mesh.point(mesh.from_vertex_handle(h))).head<2>(),
                       ToEigen(mesh.point(mesh.to_vertex_handle(h))).head<2>()});
  }
  return members;
}

void DrawMembers(const PolyMesh& mesh, SvgCanvas* canvas) {
  const Stroke stroke = MemberStroke(mesh, *canvas);
  if (stroke.width > 0.0) canvas->Polylines(TopViewEdges(mesh), stroke, false);
}

// Top-view bounds of the reference and the mesh together.
Eigen::AlignedBox2d TopViewBounds(const SurfaceModel& surface, const PolyMesh& mesh) {
  Eigen::AlignedBox2d box = TopViewBounds(surface);
  for (const auto v : mesh.vertices()) box.extend(ToEigen(mesh.point(v)).head<2>());
  return box;
}

Status CheckPlanarityInput(const PolyMesh& mesh, double target_delta, const std::string& path) {
  if (!(target_delta > 0.0) || !std::isfinite(target_delta))
    return Status::InvalidInput(path + ": target δ must be a positive number, got " +
                                std::to_string(target_delta));
  if (mesh.n_faces() == 0) return Status::InvalidInput(path + ": the mesh has no faces");
  return Status::Ok();
}

std::vector<double> PlanarityPerFace(const PolyMesh& mesh) {
  std::vector<double> delta(mesh.n_faces());
  for (const auto f : mesh.faces()) delta[f.idx()] = PlanarityDelta(FacePoints(mesh, f));
  return delta;
}

// Log colour bar with the target marked, and the legend: faces meeting the target, δ max.
void DrawPlanarityKey(const PlanarityScale& scale, const std::vector<double>& delta,
                      SvgCanvas* canvas) {
  canvas->LogColourBar(BlueWhiteRed, scale.lo(), scale.hi(), "planarity δ", {{scale.target, "target"}});
  const long meeting = std::count_if(delta.begin(), delta.end(),
                                     [&](double d) { return d <= scale.target; });
  const double max = *std::max_element(delta.begin(), delta.end());
  std::ostringstream ok, not_ok;
  ok.precision(3);
  not_ok.precision(3);
  ok << "δ ≤ " << scale.target << " (target): " << meeting << " of " << delta.size() << " faces";
  not_ok << "δ > " << scale.target << ": " << delta.size() - meeting << " faces, δ max " << max;
  canvas->Legend({{scale.Colour(scale.lo()).Hex(), ok.str()},
                  {scale.Colour(scale.hi()).Hex(), not_ok.str()}});
}

}  // namespace

namespace {

// Top view of the grid shell, each face filled with the mean of a per-vertex value.
Status WriteFaceMeanFigure(const SurfaceModel& surface, const PolyMesh& mesh, const std::vector<double>& value,
                           const ColourScale& scale, const std::string& label, const std::string& title,
                           const std::string& path, const FigureOptions& options) {
  SvgCanvas canvas(TopViewBounds(surface, mesh), options.width_px, title);
  for (const auto f : mesh.faces()) {
    double sum = 0.0;
    for (const auto v : mesh.fv_range(f)) sum += value[v.idx()];
    canvas.Polygon(TopView(FacePoints(mesh, f)), scale.map(std::clamp(scale.T(sum / mesh.valence(f)), 0.0, 1.0)));
  }
  DrawMembers(mesh, &canvas);
  DrawFrame(surface, scale, label, &canvas);
  return canvas.Write(path);
}

}  // namespace

Status WriteComplianceFigure(const SurfaceModel& surface, const PolyMesh& mesh,
                             const std::vector<double>& nodal_compliance, double scale_max,
                             const std::string& title, const std::string& path, const FigureOptions& options) {
  PQ_RETURN_IF_ERROR(
      CheckFinite(nodal_compliance, static_cast<int>(mesh.n_vertices()), "nodal compliance", "node").WithContext(path));
  const double hi = scale_max > 0.0 ? scale_max
                                    : *std::max_element(nodal_compliance.begin(), nodal_compliance.end());
  // Each face filled with the mean compliance of its nodes (paper Fig. 9, 14).
  return WriteFaceMeanFigure(surface, mesh, nodal_compliance, ColourScale{Viridis, 0.0, hi > 0.0 ? hi : 1.0},
                             "nodal compliance [J]", title, path, options);
}

Status WriteOffsetFigure(const SurfaceModel& surface, const PolyMesh& mesh, const std::vector<double>& offset,
                         double tolerance, const std::string& title, const std::string& path,
                         const FigureOptions& options) {
  PQ_RETURN_IF_ERROR(CheckFinite(offset, static_cast<int>(mesh.n_vertices()), "normal offset", "vertex").WithContext(path));
  std::vector<double> millimetres(offset.size());
  for (size_t v = 0; v < offset.size(); ++v) millimetres[v] = 1000.0 * offset[v];
  const double extent = 1000.0 * (tolerance > 0.0 ? tolerance : 1.0);
  return WriteFaceMeanFigure(surface, mesh, millimetres, ColourScale{BlueWhiteRed, -extent, extent},
                             "normal offset [mm]", title, path, options);
}

Status WriteBucklingFigure(const SurfaceModel& surface, const PolyMesh& mesh, const std::vector<double>& amplitude,
                           const std::string& title, const std::string& path, const FigureOptions& options) {
  PQ_RETURN_IF_ERROR(CheckFinite(amplitude, static_cast<int>(mesh.n_vertices()), "buckling mode", "vertex").WithContext(path));
  return WriteFaceMeanFigure(surface, mesh, amplitude, ColourScale{Viridis, 0.0, 1.0}, "buckling mode |u| (max 1)",
                             title, path, options);
}

Status WriteUtilisationFigure(const SurfaceModel& surface, const PolyMesh& mesh,
                              const std::vector<std::pair<int, int>>& members, const std::vector<double>& eta,
                              const std::string& title, const std::string& path, const FigureOptions& options) {
  PQ_RETURN_IF_ERROR(CheckFinite(eta, static_cast<int>(members.size()), "utilisation", "member").WithContext(path));
  const ColourScale scale{Viridis, 0.0, std::max(1.0, *std::max_element(eta.begin(), eta.end()))};
  SvgCanvas canvas(TopViewBounds(surface, mesh), options.width_px, title);
  for (const auto f : mesh.faces()) canvas.Polygon(TopView(FacePoints(mesh, f)), kFaintFace);
  const double width = std::max(1.5, 2.5 * MemberStroke(mesh, canvas).width);
  for (size_t e = 0; e < members.size(); ++e) {
    const Vector2d a = ToEigen(mesh.point(VertexHandle(members[e].first))).head<2>();
    const Vector2d b = ToEigen(mesh.point(VertexHandle(members[e].second))).head<2>();
    canvas.Polylines({{a, b}}, Stroke{scale.map(std::clamp(scale.T(eta[e]), 0.0, 1.0)), width, 1.0}, false);
  }
  DrawFrame(surface, scale, "utilisation η", &canvas);
  return canvas.Write(path);
}

Status WritePlanarityFigure(const SurfaceModel& surface, const PolyMesh& mesh, double target_delta,
                            const std::string& title, const std::string& path,
                            const FigureOptions& options) {
  PQ_RETURN_IF_ERROR(CheckPlanarityInput(mesh, target_delta, path));
  const PlanarityScale scale{target_delta};
  const std::vector<double> delta = PlanarityPerFace(mesh);
  SvgCanvas canvas(TopViewBounds(surface, mesh), options.width_px, title);
  for (const auto f : mesh.faces())
    canvas.Polygon(TopView(FacePoints(mesh, f)), scale.Colour(delta[f.idx()]));
  DrawMembers(mesh, &canvas);
  DrawOutlineScaleAndNorth(surface, &canvas);
  DrawPlanarityKey(scale, delta, &canvas);
  return canvas.Write(path);
}

namespace {

// Orthographic view from azimuth kAzimuth (direction towards the viewer, from east,
// counter-clockwise) and elevation kElevation: screen right, screen up, towards the viewer.
struct ObliqueView {
  static constexpr double kAzimuth = 240.0 * M_PI / 180.0;
  static constexpr double kElevation = 35.0 * M_PI / 180.0;
  Eigen::Vector3d eye{std::cos(kElevation) * std::cos(kAzimuth),
                      std::cos(kElevation) * std::sin(kAzimuth), std::sin(kElevation)};
  Eigen::Vector3d right{-std::sin(kAzimuth), std::cos(kAzimuth), 0.0};
  Eigen::Vector3d up = eye.cross(right);
  Vector2d Project(const Eigen::Vector3d& p) const { return {p.dot(right), p.dot(up)}; }
  std::vector<Vector2d> Project(const std::vector<Eigen::Vector3d>& points) const {
    std::vector<Vector2d> out;
    for (const auto& p : points) out.push_back(Project(p));
    return out;
  }
};

// Face colour darkened by up to 20 % as the face turns away from a light above the viewer.
Rgb Shaded(Rgb colour, const std::vector<Eigen::Vector3d>& polygon, const ObliqueView& view) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // Newell
  for (size_t i = 0; i < polygon.size(); ++i)
    normal += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  const Eigen::Vector3d light = (view.eye + Eigen::Vector3d::UnitZ()).normalized();
  const double lambert = normal.norm() > 0.0 ? std::abs(normal.normalized().dot(light)) : 1.0;
  const double factor = 0.8 + 0.2 * lambert;
  const auto scale = [factor](std::uint8_t c) {
    return static_cast<std::uint8_t>(std::lround(c * factor));
  };
  return {scale(colour.r), scale(colour.g), scale(colour.b)};
}

}  // namespace

Status WriteShell3dFigure(const SurfaceModel& surface, const PolyMesh& mesh, double target_delta,
                          const std::string& title, const std::string& path,
                          const FigureOptions& options) {
  PQ_RETURN_IF_ERROR(CheckPlanarityInput(mesh, target_delta, path));
  const PlanarityScale scale{target_delta};
  const std::vector<double> delta = PlanarityPerFace(mesh);
  const ObliqueView view;
  // The reference footprint on the ground, and the bounds of everything drawn.
  Rings footprint;
  Eigen::AlignedBox2d box;
  for (const auto& loop : surface.boundary_loops()) {
    std::vector<Vector2d> ring;
    for (const auto v : loop.vertices) {
      Eigen::Vector3d p = surface.position(v.idx());
      p.z() = surface.bbox_min().z();
      ring.push_back(view.Project(p));
      box.extend(ring.back());
    }
    footprint.push_back(std::move(ring));
  }
  for (const auto v : mesh.vertices()) box.extend(view.Project(ToEigen(mesh.point(v))));
  SvgCanvas canvas(box, options.width_px, title);
  canvas.Region(footprint, "#e4e4e4");
  canvas.Polylines(footprint, Stroke{Rgb{0xa0, 0xa0, 0xa0}, 1.0, 1.0}, true);
  // Painter's order: farthest face (smallest depth along the eye direction) first.
  std::vector<std::pair<double, FaceHandle>> order;
  for (const auto f : mesh.faces())
    order.emplace_back(ToEigen(mesh.calc_face_centroid(f)).dot(view.eye), f);
  std::sort(order.begin(), order.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  const Stroke edges = MemberStroke(mesh, canvas);
  for (const auto& [depth, f] : order) {
    const std::vector<Eigen::Vector3d> polygon = FacePoints(mesh, f);
    canvas.OutlinedPolygon(view.Project(polygon), Shaded(scale.Colour(delta[f.idx()]), polygon, view),
                           edges);
  }
  canvas.ScaleBar();
  const auto axis = [&](const Eigen::Vector3d& d) { return view.Project(d); };
  canvas.AxisTriad(axis(Eigen::Vector3d::UnitX()), axis(Eigen::Vector3d::UnitY()),
                   axis(Eigen::Vector3d::UnitZ()));
  DrawPlanarityKey(scale, delta, &canvas);
  return canvas.Write(path);
}

}  // namespace pqlayout
