#include "report/figure_common.h"

#include <algorithm>
#include <cmath>

#include "geometry/planarity.h"

namespace pqlayout {
namespace figure {

using Eigen::Vector2d;

namespace {

constexpr double kSignedTolerance = 1e-3;  // a sign counts above this × the other's size
const Rgb kOutline{0, 0, 0};               // boundary outline

Rings BoundaryOutline(const SurfaceModel& surface) {
  Rings rings;
  for (const auto& loop : surface.boundary_loops()) {
    std::vector<Vector2d> ring;
    for (const auto v : loop.vertices) ring.push_back(Xy(surface, v.idx()));
    rings.push_back(std::move(ring));
  }
  return rings;
}

}  // namespace

std::vector<Eigen::Vector3d> FacePoints(const PolyMesh& mesh, FaceHandle f) {
  std::vector<Eigen::Vector3d> points;
  for (const auto v : mesh.fv_range(f)) points.push_back(ToEigen(mesh.point(v)));
  return points;
}

std::vector<double> PlanarityPerFace(const PolyMesh& mesh) {
  std::vector<double> delta(mesh.n_faces());
  for (const auto f : mesh.faces()) delta[f.idx()] = PlanarityDelta(FacePoints(mesh, f));
  return delta;
}

std::vector<double> FaceMeans(const PolyMesh& mesh, const std::vector<double>& per_vertex) {
  std::vector<double> mean(mesh.n_faces(), 0.0);
  for (const auto f : mesh.faces()) {
    double sum = 0.0;
    for (const auto v : mesh.fv_range(f)) sum += per_vertex[v.idx()];
    mean[f.idx()] = sum / mesh.valence(f);
  }
  return mean;
}

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

Eigen::Vector2d Xy(const SurfaceModel& surface, int v) { return surface.position(v).head<2>(); }

Eigen::AlignedBox2d TopViewBounds(const SurfaceModel& surface) {
  return Eigen::AlignedBox2d(surface.bbox_min().head<2>(), surface.bbox_max().head<2>());
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

}  // namespace figure
}  // namespace pqlayout
