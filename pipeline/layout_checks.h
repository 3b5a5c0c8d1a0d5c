// layout.spacing checked against the reference surface before anything is solved, so that a
// spacing that cannot give a meaningful layout is one line at once, not a flat single panel
// with compliance 0 J (too coarse), two minutes and then out of memory (too fine), or level
// lines tangled around a hole no panel can frame (a hole smaller than a panel).
#pragma once

#include <string>
#include <vector>

#include "base/status.h"
#include "geometry/surface_model.h"
#include "problems/options.h"

namespace pqlayout {

// The surface's extent in its best-fit plane (the plane of the two largest principal axes
// of its area): what a layout has to cover, in metres, long ≥ short.
struct SurfaceExtent {
  double long_side = 0.0, short_side = 0.0;
};
SurfaceExtent MeasureExtent(const SurfaceModel& surface);

// The largest distance between two vertices of boundary loop `loop`, if it is below `limit`;
// otherwise some distance ≥ limit (the search stops there).
double LoopDiameterBelow(const SurfaceModel& surface, int loop, double limit);

// What the checks and warnings below need to know of the surface, measured once.
struct SurfaceFrame {
  SurfaceExtent extent;
  // The angle, in degrees, between the vector area (Σ A_f n_f) and the vertical (±z): ~0° for a
  // roof over a level rim, 90° for one exported Y-up (Blender, Maya, glTF) or a façade.
  double facing_angle_deg = 0.0;
  int parts = 0;                 // connected parts (joined by no triangle)
  std::vector<int> part_of_vertex;
};
SurfaceFrame MeasureSurfaceFrame(const SurfaceModel& surface);

// InvalidInput naming layout.spacing (and the hole) when
// - h is more than half the extent's short side: fewer than 2 panels across the surface;
// - area / h² exceeds layout.max_panels;
// - a hole (a boundary loop inside a part) or a separate part (a loop that is its part's
//   outline, other than the surface's outer one) is less than h across: no panel can frame it.
// `source` names the surface in the message ("roof.obj" or "generator dome").
Status CheckSpacingFitsSurface(const SurfaceModel& surface, const SurfaceFrame& frame, const LayoutOptions& layout,
                               const std::string& source);

// A warning for the surface stage, or "" if none: a surface facing sideways (facing angle
// above 60°: pqlayout loads along −z, so a Y-up export is a roof loaded sideways) or larger
// than any roof (2 km: most likely millimetres read as metres).
std::string SurfaceFrameWarning(const SurfaceFrame& frame, const std::string& source);

// A warning for the surface stage, or "" if none: a reference whose mean edge is more than
// 0.6 h (a CAD render mesh exported coarsely). The guidance is computed per triangle and the
// level sets are solved on it, so the layout follows its facets: an elliptic saddle's alignment
// was 2.8° from a fine export (0.25 h), 4.6° at a mean edge of 0.75 h and 11.4° at 1.26 h; remeshing
// the facets finer does not bring it back (benchmarks/RESULTS.md, "Coarse references").
std::string CoarseReferenceWarning(double mean_edge, double h, const std::string& source);

}  // namespace pqlayout
