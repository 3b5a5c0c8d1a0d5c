// Helpers shared by the figure writers (report/figures.cc: fields on the reference surface;
// report/shell_figures.cc: the grid shell): colour scales, the top-view frame (outline,
// scale bar, north arrow, colour bar) and input checks. Internal to problems/.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/mesh.h"
#include "base/status.h"
#include "geometry/surface_model.h"
#include "report/svg_canvas.h"

namespace pqlayout {
namespace figure {

using Rings = std::vector<std::vector<Eigen::Vector2d>>;

// The colour map and value range for a field: a symmetric diverging map for values of
// both signs, viridis from min to max otherwise.
struct ColourScale {
  ColourMap map = Viridis;
  double lo = 0.0, hi = 1.0;
  double T(double value) const { return hi > lo ? (value - lo) / (hi - lo) : 0.5; }
};

ColourScale ScaleFor(const std::vector<double>& values, bool allow_diverging);

// The top view of a surface vertex, and the reference's bounding box in the top view.
Eigen::Vector2d Xy(const SurfaceModel& surface, int v);
Eigen::AlignedBox2d TopViewBounds(const SurfaceModel& surface);

// Boundary outline, scale bar and north arrow; DrawFrame adds the colour bar.
void DrawOutlineScaleAndNorth(const SurfaceModel& surface, SvgCanvas* canvas);
void DrawFrame(const SurfaceModel& surface, const ColourScale& scale, const std::string& label, SvgCanvas* canvas);

// Per face of a grid shell: its planarity δ (geometry/planarity.h), and the mean of a
// per-vertex value over its vertices (how the compliance, offset and buckling figures fill
// a face; report.html's 3D view colours its faces with the same numbers).
std::vector<Eigen::Vector3d> FacePoints(const PolyMesh& mesh, FaceHandle f);
std::vector<double> PlanarityPerFace(const PolyMesh& mesh);
std::vector<double> FaceMeans(const PolyMesh& mesh, const std::vector<double>& per_vertex);

// InvalidInput naming `name` unless values has `expected` finite entries (one per `element`).
Status CheckFinite(const std::vector<double>& values, int expected, const std::string& name,
                   const std::string& element);

}  // namespace figure
}  // namespace pqlayout
