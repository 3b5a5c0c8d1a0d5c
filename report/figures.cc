#include "report/figures.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/differential_operators.h"
#include "geometry/level_lines.h"
#include "geometry/planarity.h"
#include "geometry/streamlines.h"
#include "report/svg_canvas.h"
#include "report/figure_common.h"

namespace pqlayout {
namespace {

using Eigen::Vector2d;
using namespace figure;  // NOLINT: the shared figure helpers (report/figure_common.h)

constexpr int kColourLevels = 64;           // colour quantisation of the resampled grid
constexpr double kWeakWeight = 0.5;  // weight below this: hatched (the alignment term is weighted by w, so it is weak there)
constexpr const char* kWeakLegend = "weak guidance (weight < 0.5): alignment weighted by it";
const Rgb kMutedBrown{0xc4, 0xa2, 0x7a};    // hatch of the not-enforced region
const Stroke kStreamline{Rgb{0x30, 0x30, 0x30}, 1.1, 0.9};  // integral curves
const Stroke kFaintStreamline{Rgb{0xb0, 0xb0, 0xb0}, 0.9, 0.9};  // background curves
const Stroke kPhiLine{Rgb{0x00, 0x00, 0x00}, 1.5, 1.0};           // φ = i·h (paper: black)
const Stroke kPsiLine{Rgb{0x1f, 0x5f, 0xd6}, 1.5, 1.0};           // ψ = j·h (paper: blue)
const Stroke kSeamLine{Rgb{0xd6, 0x27, 0x28}, 1.2, 0.8};          // seams of a branched layout
const Rgb kShearedFill{0xfd, 0xbf, 0x6f};   // faces crossing below min_crossing_deg
const Rgb kFoldedFill{0x6a, 0x3d, 0x9a};    // faces where φ and ψ fold over
constexpr double kMinLevelSpacingPx = 4.0;  // closer level lines (px of 1000 px): every k-th
constexpr double kMaxLevelLines = 1000.0;   // per family, whatever the function's range



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



// The faces with weight < 0.5 as one hatched region; returns the hatch fill for the legend.
std::string DrawWeakGuidanceRegion(const SurfaceModel& surface, const std::vector<double>& weight,
                                   SvgCanvas* canvas) {
  std::vector<char> weak(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) weak[f] = weight[f] < kWeakWeight;
  const std::string hatch = canvas->HatchFill(kMutedBrown);
  canvas->Region(RegionOutline(surface, weak), hatch);
  return hatch;
}

std::vector<std::vector<Vector2d>> GuidanceCurves(const SurfaceModel& surface,
                                                  const std::vector<Eigen::Vector3d>& direction,
                                                  const FigureOptions& options,
                                                  const SvgCanvas& canvas) {
  StreamlineOptions streamlines;
  streamlines.separation = options.streamline_spacing_px * canvas.unit() / canvas.px_per_metre();
  streamlines.singularities = options.guidance_singularities;
  return EvenlySpacedStreamlines(surface, direction, streamlines);
}

// The faces of `surface` where φ and ψ cross below min_crossing_deg filled kShearedFill, those
// that fold over kFoldedFill; their legend entries (none for a set that is empty).
std::vector<LegendEntry> DrawShallowCrossings(const SurfaceModel& surface, const std::vector<double>& phi,
                                              const std::vector<double>& psi, double min_crossing_deg,
                                              SvgCanvas* canvas) {
  std::vector<char> sheared(surface.num_faces(), 0), folded(surface.num_faces(), 0);
  bool any_sheared = false, any_folded = false;
  for (int f = 0; f < surface.num_faces(); ++f) {
    const Eigen::Vector3d a = FaceGradient(surface, f, phi), b = FaceGradient(surface, f, psi);
    const double sine = surface.face_normal(f).dot(a.cross(b)) / (a.norm() * b.norm());
    folded[f] = !(sine > 0.0);
    sheared[f] = !folded[f] && std::asin(std::min(1.0, sine)) * 180.0 / M_PI < min_crossing_deg;
    any_sheared |= sheared[f] != 0, any_folded |= folded[f] != 0;
  }
  std::vector<LegendEntry> legend;
  if (any_sheared) {
    canvas->Region(RegionOutline(surface, sheared), kShearedFill.Hex());
    std::ostringstream label;
    label << "φ and ψ cross below " << min_crossing_deg << "° (sheared quads)";
    legend.push_back({kShearedFill.Hex(), label.str()});
  }
  if (any_folded) {
    canvas->Region(RegionOutline(surface, folded), kFoldedFill.Hex());
    legend.push_back({kFoldedFill.Hex(), "φ and ψ fold over (inverted quads)"});
  }
  return legend;
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

  const std::string hatch = DrawWeakGuidanceRegion(surface, weight, &canvas);
  canvas.HaloPolylines(GuidanceCurves(surface, direction, options, canvas), kStreamline);

  DrawFrame(surface, scale, magnitude_label, &canvas);
  canvas.Legend({{hatch, kWeakLegend}});
  return canvas.Write(path);
}

Status WriteLevelSetFigure(const SurfaceModel& surface, const std::vector<double>& phi,
                           const std::vector<double>& psi, double spacing,
                           const std::vector<Eigen::Vector3d>& direction,
                           const std::vector<double>& weight, const std::string& title,
                           const std::string& path, const FigureOptions& options, const SeamCut* seams,
                           const SolvedLevelSets* solved) {
  const int nf = surface.num_faces();
  const SurfaceModel& level_surface = seams != nullptr ? seams->cut() : surface;
  PQ_RETURN_IF_ERROR(CheckFinite(phi, level_surface.num_vertices(), "phi", "vertex").WithContext(path));
  PQ_RETURN_IF_ERROR(CheckFinite(psi, level_surface.num_vertices(), "psi", "vertex").WithContext(path));
  if (solved != nullptr) {
    PQ_RETURN_IF_ERROR(CheckFinite(solved->phi, solved->surface.num_vertices(), "phi", "vertex").WithContext(path));
    PQ_RETURN_IF_ERROR(CheckFinite(solved->psi, solved->surface.num_vertices(), "psi", "vertex").WithContext(path));
  }
  if (static_cast<int>(direction.size()) != nf)
    return Status::InvalidInput(path + ": direction has " + std::to_string(direction.size()) +
                                " vectors, expected " + std::to_string(nf) + " (one per face)");
  PQ_RETURN_IF_ERROR(CheckFinite(weight, nf, "weight", "face").WithContext(path));
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    return Status::InvalidInput(path + ": spacing h must be a positive number, got " +
                                std::to_string(spacing));
  SvgCanvas canvas(TopViewBounds(surface), options.width_px, title);
  const std::string hatch = DrawWeakGuidanceRegion(surface, weight, &canvas);
  const std::vector<LegendEntry> crossings =
      options.min_crossing_deg <= 0.0 ? std::vector<LegendEntry>{}
      : solved != nullptr ? DrawShallowCrossings(solved->surface, solved->phi, solved->psi, options.min_crossing_deg, &canvas)
                          : DrawShallowCrossings(level_surface, phi, psi, options.min_crossing_deg, &canvas);
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
      {hatch, kWeakLegend}};
  legend.insert(legend.end(), crossings.begin(), crossings.end());
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

}  // namespace pqlayout
