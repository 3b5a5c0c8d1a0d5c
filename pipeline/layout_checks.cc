#include "pipeline/layout_checks.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

#include "base/format_number.h"
#include "geometry/differential_operators.h"

namespace pqlayout {
namespace {

std::string Num(double v) { return ReadableNumber(v); }

// v rounded to three significant digits, up or down: a bound the message suggests must
// itself pass the check.
std::string Bound(double v, bool up) {
  if (!(v > 0.0) || !std::isfinite(v)) return Num(v);
  const double unit = std::pow(10.0, std::floor(std::log10(v)) - 2.0);
  return Num((up ? std::ceil(v / unit) : std::floor(v / unit)) * unit);
}

std::string Point(const Eigen::Vector3d& p) {
  return "(" + Num(p.x()) + ", " + Num(p.y()) + ", " + Num(p.z()) + ")";
}

// At least this many panels across the surface's short side.
constexpr double kMinPanelsAcross = 2.0;

// Per boundary loop, whether it is the outline of its connected part (the part's loop of
// largest |vector area|) rather than a hole in it.
std::vector<char> OutlineLoops(const SurfaceModel& surface, const SurfaceFrame& frame) {
  const auto& loops = surface.boundary_loops();
  std::vector<int> outline(frame.parts, -1);
  for (size_t l = 0; l < loops.size(); ++l) {
    int& best = outline[frame.part_of_vertex[loops[l].vertices.front().idx()]];
    if (best < 0 || loops[l].vector_area.norm() > loops[best].vector_area.norm()) best = static_cast<int>(l);
  }
  std::vector<char> is_outline(loops.size(), 0);
  for (const int l : outline)
    if (l >= 0) is_outline[l] = 1;
  return is_outline;
}

Status CheckHoles(const SurfaceModel& surface, const SurfaceFrame& frame, double h, const std::string& source) {
  const auto& loops = surface.boundary_loops();
  const std::vector<char> is_outline = OutlineLoops(surface, frame);
  for (size_t l = 0; l < loops.size(); ++l) {
    if (loops[l].is_outer) continue;
    const double diameter = LoopDiameterBelow(surface, static_cast<int>(l), h);
    if (diameter >= h) continue;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto v : loops[l].vertices) centre += surface.position(v.idx());
    centre /= static_cast<double>(loops[l].vertices.size());
    const std::string where = source + ": boundary loop " + std::to_string(l) + " at " + Point(centre) + ", " +
                              Num(diameter) + " m across";
    const std::string remedy = " or use layout.spacing < " + Bound(diameter, false) + " m";
    if (is_outline[l])
      return Status::InvalidInput("layout.spacing: " + Num(h) + " m is larger than a separate part of the surface (" +
                                  where + ", joined to the rest by no triangle): no panel can frame it; delete it " +
                                  "from the mesh" + remedy);
    return Status::InvalidInput("layout.spacing: " + Num(h) + " m is larger than a hole in the surface (" + where +
                                "): no panel can frame it and the level lines tangle around it; fill the hole in " +
                                "the mesh" + remedy);
  }
  return Status::Ok();
}

constexpr double kLargestRoof = 2000.0;  // metres
constexpr double kSidewaysDeg = 60.0;

// No roof is kilometres across: a surface that is was most likely exported in millimetres
// (a 20 m dome read as 20 km: layout.max_panels refuses it, and this says why).
std::string UnitsHint(const SurfaceExtent& extent) {
  if (!(extent.long_side > kLargestRoof)) return "";
  return " (the surface is " + Num(extent.long_side) + " m across: if the file is in millimetres, scale it by 0.001; "
         "pqlayout reads metres)";
}

}  // namespace

SurfaceExtent MeasureExtent(const SurfaceModel& surface) {
  // Principal axes of the area: second moments of the face centroids, weighted by area.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centroid(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    centroid[f] = (surface.position(ids[0]) + surface.position(ids[1]) + surface.position(ids[2])) / 3.0;
    mean += surface.face_area(f) * centroid[f];
  }
  mean /= surface.total_area();
  Eigen::Matrix3d moments = Eigen::Matrix3d::Zero();
  for (int f = 0; f < surface.num_faces(); ++f)
    moments += surface.face_area(f) * (centroid[f] - mean) * (centroid[f] - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axes(moments);  // eigenvalues ascending
  const Eigen::Vector3d u = axes.eigenvectors().col(2), w = axes.eigenvectors().col(1);
  double u_lo = INFINITY, u_hi = -INFINITY, w_lo = INFINITY, w_hi = -INFINITY;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Eigen::Vector3d p = surface.position(v) - mean;
    u_lo = std::min(u_lo, p.dot(u)), u_hi = std::max(u_hi, p.dot(u));
    w_lo = std::min(w_lo, p.dot(w)), w_hi = std::max(w_hi, p.dot(w));
  }
  SurfaceExtent extent;
  extent.long_side = std::max(u_hi - u_lo, w_hi - w_lo);
  extent.short_side = std::min(u_hi - u_lo, w_hi - w_lo);
  return extent;
}

double LoopDiameterBelow(const SurfaceModel& surface, int loop, double limit) {
  const auto& vertices = surface.boundary_loops()[loop].vertices;
  double diameter = 0.0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Eigen::Vector3d p = surface.position(vertices[i].idx());
    for (size_t j = i + 1; j < vertices.size(); ++j) {
      diameter = std::max(diameter, (surface.position(vertices[j].idx()) - p).norm());
      if (diameter >= limit) return diameter;
    }
  }
  return diameter;
}

Status CheckSpacingFitsSurface(const SurfaceModel& surface, const SurfaceFrame& frame, const LayoutOptions& layout,
                               const std::string& source) {
  const double h = layout.spacing;
  const SurfaceExtent& extent = frame.extent;
  if (h > extent.short_side / kMinPanelsAcross)
    return Status::InvalidInput("layout.spacing: " + Num(h) + " m leaves fewer than 2 panels across the surface (" +
                                source + " is " + Num(extent.long_side) + " m × " + Num(extent.short_side) +
                                " m in its best-fit plane); use layout.spacing <= " +
                                Bound(extent.short_side / kMinPanelsAcross, false) + " m");
  // area / h² can be inf for an absurdly small h: the comparison still refuses it.
  const double panels = surface.total_area() / (h * h);
  if (!(panels <= layout.max_panels)) {
    const double h_min = std::sqrt(surface.total_area() / layout.max_panels);
    return Status::InvalidInput("layout.spacing: " + Num(h) + " m would give about " + Num(panels) + " panels on the " +
                                Num(surface.total_area()) + " m² of " + source + " (area / h²), more than " +
                                "layout.max_panels = " + std::to_string(layout.max_panels) + "; use layout.spacing >= " +
                                Bound(h_min, true) + " m or raise layout.max_panels" + UnitsHint(extent));
  }
  return CheckHoles(surface, frame, h, source);
}

SurfaceFrame MeasureSurfaceFrame(const SurfaceModel& surface) {
  SurfaceFrame frame;
  frame.extent = MeasureExtent(surface);
  Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
  for (int f = 0; f < surface.num_faces(); ++f) vector_area += surface.face_area(f) * surface.face_normal(f);
  const double norm = vector_area.norm();
  frame.facing_angle_deg = norm > 0.0 ? std::acos(std::min(1.0, std::abs(vector_area.z()) / norm)) * 180.0 / M_PI
                                      : 90.0;  // a closed or saddle-balanced surface: no side faces up
  frame.parts = ConnectedComponents(surface, &frame.part_of_vertex);
  return frame;
}

std::string SurfaceFrameWarning(const SurfaceFrame& frame, const std::string& source) {
  const SurfaceExtent& extent = frame.extent;
  if (extent.long_side > kLargestRoof)
    return "surface: " + source + " is " + Num(extent.long_side) + " m across, larger than any roof: if the file is in "
           "millimetres, scale it by 0.001 (pqlayout reads metres)";
  const double facing = frame.facing_angle_deg;
  if (facing > kSidewaysDeg)
    return "surface: " + source + " faces sideways (its area points " + Num(facing) + "° from the vertical): pqlayout "
           "takes z as up and loads along −z, so a roof exported Y-up (Blender, Maya, glTF) is loaded sideways; rotate it "
           "so that z points up (a façade can stay as it is)";
  return "";
}

std::string CoarseReferenceWarning(double mean_edge, double h, const std::string& source) {
  constexpr double kCoarseReference = 0.6;  // × h; the corpus's and the examples' references are ≤ 0.53 h
  if (!(mean_edge > kCoarseReference * h)) return "";
  return "surface: " + source + "'s triangles are coarse for panels " + Num(h) + " m apart (mean edge " + Num(mean_edge) +
         " m, " + Num(mean_edge / h) + " h): the guidance is computed per triangle, so the layout follows the facets and "
         "aligns worse; " + (source.rfind("generator", 0) == 0 ? "set surface.edge_length ≤ " + Num(0.5 * h)
                                                                         : std::string("export the surface finer (mean edge ≤ 0.5 h)"));
}

}  // namespace pqlayout
