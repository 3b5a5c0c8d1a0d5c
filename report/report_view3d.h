// The 3D view of report.html: the final grid shell (quads.obj) in WebGL through three.js
// (inlined from the Debian package libjs-three: report/embedded_js.h), to rotate (left
// drag), zoom (wheel) and pan (right or shift drag) with three.js's OrbitControls. Faces
// are coloured by a metric picked from a <select>, with the figures' scales and numbers:
//   nodal compliance  per node from analyze, each face the mean of its nodes (as
//                     compliance.svg), viridis from 0 to the nodes' maximum;
//   planarity δ       per face (PlanarityPerFace), on PlanarityScale's log scale;
//   normal offset     per vertex from stiffen (the stiffened shell from the planarised one
//                     along the reference's normal; quads.obj and quads_planarized.obj
//                     share their vertex and face order), face means as offset.svg,
//                     ± stiffen.tolerance; only when stiffen ran with a tolerance > 0.
// Members are drawn as lines, the reference surface (surface.obj) faint behind the shell
// (coarsened above kMaxSurfaceTriangles triangles) with its boundary, and a colour bar gives
// the scale's ends and units and the metric's min and max over the faces.
//
// The data travel as one <script type="application/json">: vertex coordinates relative to
// the shell's centre (%.6g: 0.1 mm at 100 m), faces as flat index lists, metric values per
// face (%.4g), and each colour map sampled at 33 stops, so the page draws the colours the
// C++ figures draw. About 70 bytes per face with all three metrics, up to ~100 kB for the
// reference, and 0.88 MB of three.js: the Great Court's page (675 faces) gains ~1 MB.
//
// Self-check: once drawn, the view's script (report/report_view3d.js) measures it as
// the figures are measured (report_html.h): the canvas (preserveDrawingBuffer) scaled onto
// a 2D canvas, its fraction of non-white pixels (ink) and distinct colours; then it turns
// the camera by 30° about the vertical, draws, counts the fraction of pixels that changed
// (rotated), and turns it back. The result goes into the section's data-check attribute
// ("w=.. h=.. faces=.. ink=.. colours=.. rotated=.."; "nowebgl" or "error ..." otherwise),
// read by scripts/check_report.sh. Without WebGL the section says so in one line.
#pragma once

#include <string>
#include <vector>

#include "geometry/mesh.h"
#include "geometry/surface_model.h"

namespace pqlayout {

// What the view draws; every pointer is borrowed and may be null (that part is left out).
struct View3dData {
  const PolyMesh* shell = nullptr;                        // the final grid shell: no view without faces
  const SurfaceModel* surface = nullptr;                  // the reference, drawn faint
  double target_delta = 1e-3;                             // planarize.target_delta: the δ scale
  const std::vector<double>* nodal_compliance = nullptr;  // per shell vertex, J
  const std::vector<double>* normal_offset = nullptr;     // per shell vertex, m
  double offset_tolerance = 0.0;                          // stiffen.tolerance, m; 0: stiffen off, no offset
};

// Above this many triangles the page gets a coarser copy of the reference surface (vertex
// clustering), to keep report.html small: a triangle costs ~30 bytes, and the Great Court's
// reference has 12k (the faint backdrop needs no more than a few thousand).
constexpr int kMaxSurfaceTriangles = 4000;

// The report's 3D section, <section id="view3d" data-faces="N">...</section> with the data,
// three.js and the view's script; "" if data.shell is null or has no faces. A metric whose
// values are missing, of the wrong count or not finite is left out of the <select>.
std::string View3dHtml(const View3dData& data);

}  // namespace pqlayout
