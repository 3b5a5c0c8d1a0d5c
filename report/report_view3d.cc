#include "report/report_view3d.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "report/embedded_js.h"
#include "report/figure_common.h"
#include "report/figures.h"

namespace pqlayout {
namespace {

constexpr int kColourStops = 33;  // samples of each colour map for the page (t = 0, 1/32, ..., 1)

// One metric of the <select>: a value per face and its colour scale.
struct FaceMetric {
  std::string name, unit;
  bool log = false;  // logarithmic scale between lo and hi (planarity δ)
  double lo = 0.0, hi = 1.0;
  ColourMap map = Viridis;
  std::vector<double> values;  // per face
  double mark = 0.0;           // a value marked on the colour bar (0: none)
  std::string mark_label;
};

void AppendNumber(std::string* out, double value, int digits) {
  if (!std::isfinite(value)) {
    *out += "null";
    return;
  }
  char text[32];
  std::snprintf(text, sizeof(text), "%.*g", digits, value);
  *out += text;
}

// "[a,b,c]" of the values, each with `digits` significant digits.
std::string NumberList(const std::vector<double>& values, int digits) {
  std::string out = "[";
  for (size_t i = 0; i < values.size(); ++i) {
    if (i > 0) out += ',';
    AppendNumber(&out, values[i], digits);
  }
  return out + "]";
}

std::string IntList(const std::vector<int>& values) {
  std::string out = "[";
  for (size_t i = 0; i < values.size(); ++i) out += (i > 0 ? "," : "") + std::to_string(values[i]);
  return out + "]";
}

void AppendPoint(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, std::vector<double>* out) {
  for (int k = 0; k < 3; ++k) out->push_back(p[k] - centre[k]);
}

// "vertices": coordinates relative to `centre`, "faces": [n, i_1..i_n, n, ...].
std::string ShellJson(const PolyMesh& mesh, const Eigen::Vector3d& centre) {
  std::vector<double> xyz;
  for (const auto v : mesh.vertices()) AppendPoint(ToEigen(mesh.point(v)), centre, &xyz);
  std::vector<int> faces;
  for (const auto f : mesh.faces()) {
    faces.push_back(static_cast<int>(mesh.valence(f)));
    for (const auto v : mesh.fv_range(f)) faces.push_back(v.idx());
  }
  return "\"vertices\":" + NumberList(xyz, 6) + ",\"faces\":" + IntList(faces);
}

// Triangles for the page: points and three corner indices each.
struct Triangles {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> corners;
};

// The reference's triangles merged by vertex clustering on a grid of `cell` (m) cubes: each
// occupied cube's vertices become one at their mean, triangles left with fewer than three
// distinct corners drop out, duplicates are kept once. Crude (it may fold or gap the
// surface), which is fine for a faint backdrop.
Triangles ClusterSurface(const SurfaceModel& surface, double cell) {
  Triangles out;
  std::map<std::array<long, 3>, int> cluster_of_cube;
  std::vector<int> cluster(surface.num_vertices());
  std::vector<int> members;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Eigen::Vector3d p = surface.position(v);
    const std::array<long, 3> cube{std::lround(std::floor(p.x() / cell)), std::lround(std::floor(p.y() / cell)),
                                   std::lround(std::floor(p.z() / cell))};
    const auto [it, added] = cluster_of_cube.emplace(cube, static_cast<int>(out.points.size()));
    if (added) {
      out.points.push_back(Eigen::Vector3d::Zero());
      members.push_back(0);
    }
    cluster[v] = it->second;
    out.points[it->second] += p;
    ++members[it->second];
  }
  for (size_t c = 0; c < out.points.size(); ++c) out.points[c] /= members[c];
  std::set<std::array<int, 3>> seen;
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto [a, b, c] = surface.face_vertices(f);
    std::array<int, 3> t{cluster[a], cluster[b], cluster[c]};
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    std::array<int, 3> key = t;
    std::sort(key.begin(), key.end());
    if (seen.insert(key).second) out.corners.insert(out.corners.end(), t.begin(), t.end());
  }
  return out;
}

// The reference as at most kMaxSurfaceTriangles triangles: itself if it has no more, else
// clustered on cubes sized for about that many (a plane of area A in cubes of side c keeps
// ~2A/c² triangles), growing them until it fits.
Triangles PageSurface(const SurfaceModel& surface) {
  if (surface.num_faces() <= kMaxSurfaceTriangles) {
    Triangles all;
    for (int v = 0; v < surface.num_vertices(); ++v) all.points.push_back(surface.position(v));
    for (int f = 0; f < surface.num_faces(); ++f)
      for (const int v : surface.face_vertices(f)) all.corners.push_back(v);
    return all;
  }
  double cell = std::sqrt(2.0 * surface.total_area() / kMaxSurfaceTriangles);
  for (int attempt = 0; attempt < 20 && std::isfinite(cell) && cell > 0.0; ++attempt, cell *= 1.2) {
    Triangles coarse = ClusterSurface(surface, cell);
    if (static_cast<int>(coarse.corners.size()) <= 3 * kMaxSurfaceTriangles) return coarse;
  }
  return {};  // degenerate input: the boundary only
}

// "surface": its triangles (PageSurface) and its boundary loops.
std::string SurfaceJson(const SurfaceModel& surface, const Eigen::Vector3d& centre) {
  const Triangles triangles = PageSurface(surface);
  std::vector<double> xyz;
  for (const auto& p : triangles.points) AppendPoint(p, centre, &xyz);
  std::string out = "\"surface\":{\"vertices\":" + NumberList(xyz, 5) + ",\"triangles\":" +
                    IntList(triangles.corners) + ",\"boundary\":[";
  for (size_t l = 0; l < surface.boundary_loops().size(); ++l) {
    std::vector<double> loop;
    for (const auto v : surface.boundary_loops()[l].vertices) AppendPoint(surface.position(v.idx()), centre, &loop);
    out += (l > 0 ? "," : "") + NumberList(loop, 5);
  }
  return out + "]}";
}

std::string MetricJson(const FaceMetric& m) {
  const auto [min, max] = std::minmax_element(m.values.begin(), m.values.end());
  std::string out = "{\"name\":" + nlohmann::json(m.name).dump() + ",\"unit\":" + nlohmann::json(m.unit).dump() +
                    ",\"log\":" + (m.log ? "true" : "false") + ",\"lo\":";
  AppendNumber(&out, m.lo, 6);
  out += ",\"hi\":";
  AppendNumber(&out, m.hi, 6);
  out += ",\"min\":";
  AppendNumber(&out, *min, 6);
  out += ",\"max\":";
  AppendNumber(&out, *max, 6);
  if (m.mark > 0.0) {
    out += ",\"mark\":";
    AppendNumber(&out, m.mark, 6);
    out += ",\"mark_label\":" + nlohmann::json(m.mark_label).dump();
  }
  out += ",\"stops\":[";
  for (int i = 0; i < kColourStops; ++i)
    out += (i > 0 ? ",\"" : "\"") + m.map(static_cast<double>(i) / (kColourStops - 1)).Hex() + "\"";
  return out + "],\"values\":" + NumberList(m.values, 4) + "}";
}

// One value per vertex, all finite: a per-vertex metric can be drawn.
bool UsablePerVertex(const std::vector<double>* values, const PolyMesh& mesh) {
  return values != nullptr && values->size() == mesh.n_vertices() &&
         std::all_of(values->begin(), values->end(), [](double v) { return std::isfinite(v); });
}

// The metrics the data allow, the first one shown first: the compliance (the paper's
// Fig. 9/14), planarity δ, the normal offset; scales as in the SVG figures.
std::vector<FaceMetric> Metrics(const View3dData& data) {
  const PolyMesh& mesh = *data.shell;
  std::vector<FaceMetric> metrics;
  if (UsablePerVertex(data.nodal_compliance, mesh)) {
    const double max = *std::max_element(data.nodal_compliance->begin(), data.nodal_compliance->end());
    metrics.push_back({"nodal compliance (face mean of its nodes)", "J", false, 0.0, max > 0.0 ? max : 1.0, Viridis,
                       figure::FaceMeans(mesh, *data.nodal_compliance), 0.0, ""});
  }
  if (data.target_delta > 0.0 && std::isfinite(data.target_delta)) {
    const PlanarityScale scale{data.target_delta};
    metrics.push_back({"planarity δ (log scale)", "", true, scale.lo(), scale.hi(), BlueWhiteRed,
                       figure::PlanarityPerFace(mesh), scale.target, "target"});
  }
  if (data.offset_tolerance > 0.0 && UsablePerVertex(data.normal_offset, mesh)) {
    std::vector<double> millimetres = figure::FaceMeans(mesh, *data.normal_offset);
    for (double& value : millimetres) value *= 1000.0;
    const double extent = 1000.0 * data.offset_tolerance;
    metrics.push_back({"normal offset from the planarised grid (face mean)", "mm", false, -extent, extent,
                       BlueWhiteRed, std::move(millimetres), 0.0, ""});
  }
  return metrics;
}

std::string DataJson(const View3dData& data) {
  Eigen::AlignedBox3d box;
  for (const auto v : data.shell->vertices()) box.extend(ToEigen(data.shell->point(v)));
  Eigen::Vector3d centre = box.center();
  if (!centre.allFinite()) centre.setZero();
  std::string out = "{\"centre\":" + NumberList({centre.x(), centre.y(), centre.z()}, 10) + "," +
                    ShellJson(*data.shell, centre);
  if (data.surface != nullptr) out += "," + SurfaceJson(*data.surface, centre);
  out += ",\"metrics\":[";
  const std::vector<FaceMetric> metrics = Metrics(data);
  for (size_t i = 0; i < metrics.size(); ++i) out += (i > 0 ? "," : "") + MetricJson(metrics[i]);
  return out + "]}";
}

const char* kStyle = R"(<style>
#view3d .v3d-controls{display:flex;flex-wrap:wrap;gap:0.4em 1.2em;align-items:center;margin:0.3em 0}
#view3d .v3d-help{color:#666;font-size:0.9em}
#view3d .v3d-canvas{width:100%;height:600px;border:1px solid #ddd;touch-action:none}
#view3d .v3d-canvas canvas{display:block}
#view3d .v3d-key{display:flex;align-items:center;gap:0.6em;margin-top:0.4em;font-size:0.92em;color:#333}
#view3d .v3d-bar{position:relative;display:inline-block;width:320px;height:14px;border:1px solid #999}
#view3d .v3d-mark{position:absolute;top:-4px;bottom:-4px;border-left:2px solid #222}
#view3d .v3d-note{color:#555;margin:0.3em 0}
</style>
)";

const char* kMarkup = R"(<div class="v3d-controls"><label>colour by <select class="v3d-metric"></select></label>
<label><input type="checkbox" class="v3d-members" checked> members</label>
<label><input type="checkbox" class="v3d-reference" checked> reference surface</label>
<button type="button" class="v3d-reset">reset view</button>
<span class="v3d-help">drag: rotate · wheel: zoom · right drag or shift drag: pan</span></div>
<div class="v3d-canvas"></div>
<div class="v3d-key"><span class="v3d-lo"></span><span class="v3d-bar"><span class="v3d-mark"></span></span>
<span class="v3d-hi"></span><span class="v3d-label"></span></div>
<p class="v3d-note"></p>
)";

}  // namespace

std::string View3dHtml(const View3dData& data) {
  if (data.shell == nullptr || data.shell->n_faces() == 0) return "";
  std::string html = "<h2>3D view</h2>\n<section id=\"view3d\" data-faces=\"" +
                     std::to_string(data.shell->n_faces()) + "\">\n" + kStyle + kMarkup;
  // The JSON holds numbers and escaped strings only; "</" cannot end the element early.
  std::string json = DataJson(data);
  for (size_t at = json.find("</"); at != std::string::npos; at = json.find("</", at)) json.replace(at, 2, "<\\/");
  html += "<script type=\"application/json\" id=\"view3d-data\">" + json + "</script>\n<script>";
  html += embedded::ThreeJs();
  html += "</script>\n<script>";
  html += embedded::OrbitControlsJs();
  html += "</script>\n<script>";
  html += embedded::View3dJs();  // report/report_view3d.js
  return html + "</script>\n</section>\n";
}

}  // namespace pqlayout
