// Stage `guidance`: the guidance field (problems/guidance.h) of the configured source, its
// metrics (singularities, sources), fields/vertices.csv, fields/faces.csv, fields.vtk and
// figures/guidance.svg.
#include <glog/logging.h>

#include <algorithm>
#include <map>
#include <sstream>

#include "geometry/field_writers.h"
#include "geometry/line_field_singularities.h"
#include "geometry/scalar_field_extrema.h"
#include "pipeline/stages.h"
#include "problems/guidance.h"
#include "report/figures.h"

namespace pqlayout {

namespace {

Status WriteGuidanceOutputs(const SurfaceModel& surface, const Eigen::Vector3d& origin, const std::vector<double>& v_z,
                            const GuidanceField& g, OutputFiles* out) {
  std::vector<double> x(surface.num_vertices()), y(x.size()), z(x.size()), zero(x.size(), 0.0);
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Eigen::Vector3d p = surface.position(v) + origin;  // the file's coordinates
    x[v] = p.x(), y[v] = p.y(), z[v] = p.z();
  }
  PQ_RETURN_IF_ERROR(WriteCsvTable({"id", "x", "y", "z", "vx", "vy", "vz"}, {&x, &y, &z, &zero, &zero, &v_z},
                                   out->Path("fields/vertices.csv")));
  std::vector<double> dx(surface.num_faces()), dy(dx.size()), dz(dx.size());
  for (int f = 0; f < surface.num_faces(); ++f) dx[f] = g.direction[f].x(), dy[f] = g.direction[f].y(), dz[f] = g.direction[f].z();
  return WriteCsvTable({"id", "dx", "dy", "dz", "strain_max", "strain_min", "weight"},
                       {&dx, &dy, &dz, &g.major, &g.minor, &g.weight}, out->Path("fields/faces.csv"));
}

nlohmann::json SingularityMetrics(const SurfaceModel& surface, const GuidanceField& g) {
  const auto singularities = FindLineFieldSingularities(surface, g.direction);
  nlohmann::json list = nlohmann::json::array();
  std::map<std::string, int> by_index;
  for (const auto& s : singularities) {
    std::ostringstream index;
    index << std::showpos << s.index;
    ++by_index[index.str()];
    list.push_back({{"vertex", s.vertex}, {"index", s.index}, {"x", s.position.x()}, {"y", s.position.y()}});
  }
  return {{"count", singularities.size()}, {"by_index", by_index}, {"list", list}};
}

// The sources of the guidance field (paper Fig. 6): the points where its integral curves
// converge, i.e. where the field's magnitude (|ε_max|) vanishes. Counted robustly as the
// interior minima of the magnitude (averaged to the vertices) whose persistence exceeds
// 2 % of the largest magnitude.
nlohmann::json SourceMetrics(const SurfaceModel& surface, const GuidanceField& g) {
  std::vector<double> at_vertex(surface.num_vertices(), 0.0), area(surface.num_vertices(), 0.0);
  for (int f = 0; f < surface.num_faces(); ++f) {
    for (const int v : surface.face_vertices(f)) {
      at_vertex[v] += surface.face_area(f) * g.magnitude[f];
      area[v] += surface.face_area(f);
    }
  }
  for (int v = 0; v < surface.num_vertices(); ++v) at_vertex[v] /= area[v];
  nlohmann::json list = nlohmann::json::array();
  for (const auto& m : PersistentMinima(surface, at_vertex, 0.02 * g.scale)) {
    const Eigen::Vector3d p = surface.position(m.vertex);
    list.push_back({{"vertex", m.vertex}, {"x", p.x()}, {"y", p.y()}, {"magnitude", m.value}});
  }
  return list;
}

}  // namespace

Status RunGuidanceStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  SurfaceModel& surface = *state->surface;
  const GuidanceOptions& options = state->config.guidance;
  const std::vector<double> v_z = surface.VertexFieldValues("v_z");
  GuidanceField& g = state->guidance;
  if (options.source == "strain") PQ_RETURN_IF_ERROR(ComputeStrainGuidance(surface, v_z, options, &g));
  else if (options.source == "curvature") PQ_RETURN_IF_ERROR(ComputeCurvatureGuidance(surface, options, &g));
  else PQ_RETURN_IF_ERROR(ReadGuidanceFile(surface, options, &g));
  if (options.source == "curvature") {
    const double h = state->config.layout.spacing;
    const int swapped = CombCurvatureNet(surface, h * h, &g);
    LOG(INFO) << "guidance: curvature net combed, " << swapped << " faces follow the other family";
  }
  const bool fallback = options.fallback == "curvature" && options.source != "curvature";
  double fallback_area = 0.0;
  if (fallback) {
    GuidanceField curvature;
    PQ_RETURN_IF_ERROR(ComputeCurvatureGuidance(surface, options, &curvature));
    fallback_area = AddCurvatureFallback(surface, curvature, options.fallback_weight, &g);
  }

  double weight_sum = 0.0, area_above_half = 0.0;
  int faces_above_half = 0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    weight_sum += g.weight[f];
    if (g.weight[f] > 0.5) {
      ++faces_above_half;
      area_above_half += surface.face_area(f);
    }
  }
  *metrics = {{"source", options.source},
              {"scale", g.scale},
              {"max_principal", g.major.empty() ? 0.0 : *std::max_element(g.magnitude.begin(), g.magnitude.end())},
              {"weight_mean", weight_sum / surface.num_faces()},
              {"faces_weight_above_half", static_cast<double>(faces_above_half) / surface.num_faces()},
              {"area_weight_above_half", area_above_half / surface.total_area()},
              {"singularities", SingularityMetrics(surface, g)},
              {"fallback", fallback ? options.fallback : "none"},
              {"area_fallback", fallback_area}};
  (*metrics)["sources"] = SourceMetrics(surface, g);
  (*metrics)["n_sources"] = (*metrics)["sources"].size();
  LOG(INFO) << "guidance: " << options.source
            << (fallback ? ", curvature lines where it is weak (" + std::to_string(std::lround(100.0 * fallback_area)) +
                               " % of the area)"
                         : std::string())
            << ", " << 100.0 * faces_above_half / surface.num_faces()
            << " % of faces with weight > 0.5, " << (*metrics)["singularities"]["count"] << " singularities "
            << (*metrics)["singularities"]["by_index"].dump()
            << ", " << (*metrics)["n_sources"] << " sources (minima of the field's magnitude)";
  if (state->config.output.fields) PQ_RETURN_IF_ERROR(WriteGuidanceOutputs(surface, state->origin, v_z, g, out));
  const bool strain = options.source == "strain";
  // (The fallback's title drops "(integral curves)": the long one ran off the figure.)
  const std::string title = fallback ? "Guidance: " + options.source + "; curvature lines where weak"
                            : strain ? "Guidance: principal strain directions (integral curves)"
                                     : "Guidance: " + options.source + " directions (integral curves)";
  const std::string label = strain ? "|ε_max|" : options.source == "curvature" ? "|κ1 − κ2| [1/m]" : "|d|";
  return WriteGuidanceFigure(surface, g.direction, g.magnitude, label, g.weight, title,
                             out->Path("figures/guidance.svg"));
}

}  // namespace pqlayout
