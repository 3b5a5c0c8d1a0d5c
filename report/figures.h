// Figure compositions for the pipeline stages, drawn as self-contained SVG top views
// (SvgCanvas): the membrane displacement v_z (paper Fig. 3) and the guidance field with
// its integral curves and the regions where alignment is not enforced (paper Fig. 6), and
// the level lines of the layout's two functions φ, ψ over the guidance (paper Figs. 7, 12),
// and of the grid shell: planarity δ before/after planarisation (Fig. 8/13) and as an
// oblique 3D view, nodal compliance (Fig. 9/14), stiffen's offset, the buckling mode and
// the member utilisation. Written in report/figures.cc (the reference surface's fields)
// and report/shell_figures.cc (the grid shell), sharing report/figure_common.h.
//
// Size: face fields of the reference (guidance magnitude): up to
// FigureOptions::max_face_polygons faces every face is one <path> element
// (~65 bytes); above, faces are too small to see one by one anyway (200k faces on a
// 1000 px drawing are ~2 px each), so the colour field is resampled onto a regular grid
// of grid_cell_px squares in the top view, quantised to 64 colour levels, and runs of
// equal colour along a row are merged into one box. Vertex fields (v_z) always take the
// grid path, interpolated linearly inside each triangle. Regions (the low-weight faces) are
// drawn as their merged outline, streamlines at a density set in px. A 1M-triangle input
// thus gives a file of a few MB, independent of the face count. Level lines are one path
// per family with one subpath per chained line (geometry/level_lines.h), points closer than
// 0.6 px dropped, and at most one line per few px: their size depends on the drawing and
// the spacing h, not on the face count. Grid-shell figures draw every face (their count is
// set by h: hundreds to tens of thousands); member lines thin out and disappear as the
// faces get small on the drawing (MeshLineWidth).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/mesh.h"
#include "base/status.h"
#include "geometry/line_field_singularities.h"
#include "geometry/seams.h"
#include "geometry/surface_model.h"
#include "report/svg_canvas.h"

namespace pqlayout {

struct FigureOptions {
  double width_px = 1000.0;             // drawing width; fonts, strokes, spacings scale with it
  int max_face_polygons = 200000;       // above this face count, resample onto a grid
  double grid_cell_px = 2.0;            // grid square size (px of a 1000 px drawing)
  double streamline_spacing_px = 16.0;  // distance between integral curves (px of 1000 px)
  double min_crossing_deg = 0.0;        // level-set figure: faces crossing below this filled (0: none)
  // Planarity figure: faces (indices) circled by a thick outline with a legend entry
  // `marked_label`, e.g. the panels planarisation folded (none: no outline, no entry).
  std::vector<int> marked_faces;
  std::string marked_label;
  // Guidance and level-set figures: the singularities of `direction` on `surface` if already
  // found (the guidance stage's, GuidanceField::singularities), else null: found again.
  const std::vector<LineFieldSingularity>* guidance_singularities = nullptr;
};

// Paper Fig. 3: top view, v_z per vertex (metres) as a smooth colour map (always resampled
// onto the grid, interpolated linearly inside each triangle, 64 colour bands: no faceting
// at any face count; values of both signs use a diverging map symmetric about 0,
// one-signed values viridis), colour bar "v_z [mm]", title, scale bar, north arrow,
// boundary outline in black. InvalidInput if v_z does not have one finite value per vertex.
Status WriteDisplacementFigure(const SurfaceModel& surface, const std::vector<double>& v_z,
                               const std::string& title, const std::string& path,
                               const FigureOptions& options = {});

// Paper Fig. 6: top view; faces coloured by `magnitude` (viridis, colour bar labelled
// `magnitude_label`); faces with weight < 0.5 (weak guidance: the alignment term is weighted by w) hatched in a muted
// brown with a legend entry; evenly spaced integral curves of the line field `direction`
// in dark grey on top; boundary outline; scale bar; north arrow; title. InvalidInput if
// `direction` does not have one vector per face (zero vectors: no field there) or
// `magnitude` or `weight` does not have one finite value per face.
Status WriteGuidanceFigure(const SurfaceModel& surface,
                           const std::vector<Eigen::Vector3d>& direction,
                           const std::vector<double>& magnitude, const std::string& magnitude_label,
                           const std::vector<double>& weight, const std::string& title,
                           const std::string& path, const FigureOptions& options = {});

// φ and ψ per vertex of the mesh they were solved on (WriteLevelSetFigure's crossing marks).
struct SolvedLevelSets {
  const SurfaceModel& surface;
  const std::vector<double>& phi;
  const std::vector<double>& psi;
};

// Paper Figs. 7 and 12: top view on white; faces with weight < 0.5 (alignment not
// enforced) hatched in muted brown as in the guidance figure; evenly spaced integral curves
// of `direction` faint grey in the background; the level lines φ = i·h (black) and ψ = j·h
// (blue) for every integer i, j in range, on top; boundary outline; legend (φ lines, ψ
// lines, guidance, unaligned region); scale bar; north arrow; title. φ and ψ follow the
// levelset stage's convention |∇φ| ≈ |∇ψ| ≈ 1/h, so the line φ = i·h (metres) is the level
// φ = i of the stored values. If the lines would come closer than a few px (h tiny for the
// drawing, or a diverged function with a huge range), only every k-th is drawn and the
// legend says so. InvalidInput if φ or ψ does not have one finite value per vertex,
// `direction` one vector per face, `weight` one finite value per face, or spacing is not a
// positive number.
// With options.min_crossing_deg > 0, the faces where φ's and ψ's lines cross at less than
// that angle are filled light orange under the lines (sheared quads), and those where they
// fold over (n · (∇φ × ∇ψ) ≤ 0: inverted quads) purple; legend entries only if there are any.
// They are measured on `solved` if given (the mesh the level sets were solved on, whose faces
// report.json counts), else on the mesh the lines are drawn on.
// seams (optional, geometry/seams.h): φ, ψ are then per vertex of seams->cut(), the lines
// are traced on the cut surface (they meet across the seams), and the seams are drawn in red
// with their branch points (interior ends) as dots.
Status WriteLevelSetFigure(const SurfaceModel& surface, const std::vector<double>& phi,
                           const std::vector<double>& psi, double spacing,
                           const std::vector<Eigen::Vector3d>& direction,
                           const std::vector<double>& weight, const std::string& title,
                           const std::string& path, const FigureOptions& options = {},
                           const SeamCut* seams = nullptr, const SolvedLevelSets* solved = nullptr);

// Paper Fig. 9/14: top view of the grid shell, each face filled with the mean nodal
// compliance of its nodes, members drawn as thin dark lines, reference outline, colour bar
// "nodal compliance [J]" from 0 to scale_max (pass the same value for two layouts to make
// them comparable; ≤ 0: this layout's own maximum), scale bar, north arrow, title.
Status WriteComplianceFigure(const SurfaceModel& surface, const PolyMesh& mesh,
                             const std::vector<double>& nodal_compliance, double scale_max,
                             const std::string& title, const std::string& path, const FigureOptions& options = {});

// The stiffen stage's change of shape: top view of the grid shell, each face filled with the
// mean normal offset of its vertices from the planarised mesh (positive: along the
// reference's normal, up), diverging blue–white–red from −tolerance to +tolerance (mm),
// members as in the compliance figure. InvalidInput if offset has not one finite value per vertex.
Status WriteOffsetFigure(const SurfaceModel& surface, const PolyMesh& mesh, const std::vector<double>& offset,
                         double tolerance, const std::string& title, const std::string& path,
                         const FigureOptions& options = {});

// The first buckling mode (analyze): top view, each face filled with the mean of its
// vertices' mode amplitude |u| (the mode normalised to max 1), viridis 0..1.
Status WriteBucklingFigure(const SurfaceModel& surface, const PolyMesh& mesh, const std::vector<double>& amplitude,
                           const std::string& title, const std::string& path, const FigureOptions& options = {});

// Member utilisation η (analyze): top view, faces light grey, every member (mesh vertex
// pair) drawn in its colour on viridis 0..max(1, η max), so that members over 1 are the
// brightest. InvalidInput unless eta has one finite value per member.
Status WriteUtilisationFigure(const SurfaceModel& surface, const PolyMesh& mesh,
                              const std::vector<std::pair<int, int>>& members, const std::vector<double>& eta,
                              const std::string& title, const std::string& path, const FigureOptions& options = {});

// Line width (px of a 1000 px drawing) of mesh edges (grid-shell members) whose mean length
// on the drawing is `mean_edge_px` (px of a 1000 px drawing): 5 % of it, between 0.3 and
// 1.2 px, and 0 (edges not drawn, faces only) below 4 px, where lines would cover the faces;
// their opacity rises from 0.35 at 4 px to 0.9 at 15 px and above. So 300 faces on the Great
// Court get opaque 1.2 px lines, 30,000 faces (~5 px edges) faint 0.3 px ones, 100,000 none.
double MeshLineWidth(double mean_edge_px);
double MeshLineOpacity(double mean_edge_px);

// The planarity colour scale shared by planarity_initial.svg, planarity.svg and
// shell_3d.svg (paper Fig. 8/13): δ on a logarithmic scale two decades either side of the
// target δ, diverging blue–white–red with white at the target: blue faces meet it, red ones
// do not, and the same δ has the same colour before and after planarisation. δ below the
// scale (triangles: δ = 0) takes the bottom colour, above it the top one.
struct PlanarityScale {
  static constexpr double kDecades = 2.0;  // either side of the target
  double target = 1e-3;
  double lo() const;
  double hi() const;
  Rgb Colour(double delta) const;
};

// Paper Fig. 8/13: top view of the quad mesh, each face filled with its planarity δ
// (geometry/planarity.h) on PlanarityScale{target_delta}, edges as thin dark lines
// (MeshLineWidth), reference outline, log colour bar "planarity δ" with the target marked,
// legend with the number of faces meeting the target and δ max, scale bar, north arrow;
// options.marked_faces outlined (FigureOptions). InvalidInput if target_delta is not a
// positive number, the mesh has no faces or a marked face is not one of its faces.
Status WritePlanarityFigure(const SurfaceModel& surface, const PolyMesh& mesh, double target_delta,
                            const std::string& title, const std::string& path,
                            const FigureOptions& options = {});

// Oblique 3D view of the grid shell: orthographic projection seen from the south-west
// (azimuth 240°, 35° above the horizon), faces drawn back to front (painter's order by
// centroid depth) in their planarity colour (PlanarityScale), lightly shaded by their
// orientation (×0.8–1), edges as in WritePlanarityFigure; the reference footprint in light
// grey on the ground (lowest z) below; axis triad (E, N, up) instead of a north arrow; the
// scale bar holds along the drawing's horizontal. InvalidInput as WritePlanarityFigure.
Status WriteShell3dFigure(const SurfaceModel& surface, const PolyMesh& mesh, double target_delta,
                          const std::string& title, const std::string& path,
                          const FigureOptions& options = {});

}  // namespace pqlayout
