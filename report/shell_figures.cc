// The figures of the grid shell (top views of the polygon mesh: planarity, compliance,
// offset, buckling, utilisation; the oblique 3D view): report/figures.h.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "report/svg_canvas.h"
#include "report/figure_common.h"
#include "report/figures.h"

namespace pqlayout {
namespace {
using Eigen::Vector2d;
using namespace figure;  // NOLINT: the shared figure helpers (report/figure_common.h)
}  // namespace

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
  Eigen::AlignedBox2d box = figure::TopViewBounds(surface);
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

// WritePlanarityFigure's marked faces: a thick outline in a colour off the blue–white–red map.
const Rgb kMarkColour{230, 160, 0};
constexpr double kMarkWidth = 3.0;
constexpr double kMarkRing = 16.0;  // ring radius, px of the reference width

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
  const std::vector<double> mean = FaceMeans(mesh, value);
  for (const auto f : mesh.faces())
    canvas.Polygon(TopView(FacePoints(mesh, f)), scale.map(std::clamp(scale.T(mean[f.idx()]), 0.0, 1.0)));
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
  std::vector<std::vector<Vector2d>> marked;  // each face's outline and a ring round it, seen at any size
  const double ring = kMarkRing * canvas.unit() / canvas.px_per_metre();
  for (const int f : options.marked_faces) {
    if (f < 0 || f >= static_cast<int>(mesh.n_faces()))
      return Status::InvalidInput(path + ": marked face " + std::to_string(f) + " is not a face of the mesh");
    marked.push_back(TopView(FacePoints(mesh, FaceHandle(f))));
    Vector2d centre = Vector2d::Zero();
    for (const auto& p : marked.back()) centre += p / static_cast<double>(marked.back().size());
    std::vector<Vector2d> circle;
    for (int k = 0; k < 48; ++k)
      circle.push_back(centre + ring * Vector2d(std::cos(k * M_PI / 24.0), std::sin(k * M_PI / 24.0)));
    marked.push_back(std::move(circle));
  }
  const Stroke mark{kMarkColour, kMarkWidth};
  if (!marked.empty()) canvas.Polylines(marked, mark, true);
  DrawOutlineScaleAndNorth(surface, &canvas);
  DrawPlanarityKey(scale, delta, &canvas);
  if (!marked.empty())
    canvas.Legend({{kMarkColour.Hex(),
                    std::to_string(options.marked_faces.size()) + " " + options.marked_label + " (outlined, ringed)"}});
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
